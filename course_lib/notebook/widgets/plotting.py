"""Speed-over-time figures with parameter changes marked, as PNG bytes (pure matplotlib)."""

from __future__ import annotations

import io
from collections.abc import Sequence

__all__ = ["speed_png"]


def speed_png(
    times: Sequence[float],
    speeds: Sequence[float],
    marks: Sequence[tuple[float, str]],
    *,
    title: str = "Robot speed from /odom",
) -> bytes:
    """Return a PNG of speed (m/s) over simulated time (s), a dashed line at each mark."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 3), dpi=90)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.plot(list(times), list(speeds), color="#1565c0", linewidth=1.8)
    top = max([0.25, *speeds]) * 1.15
    for t, label in marks:
        ax.axvline(t, color="#c62828", linestyle="--", linewidth=1)
        ax.text(t, top * 0.97, f" {label}", color="#c62828", fontsize=8, va="top", rotation=0)
    ax.set_ylim(-0.02, top)
    ax.set_xlabel("simulated time (s)")
    ax.set_ylabel("speed (m/s)")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()
