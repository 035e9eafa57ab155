"""Speed-over-time figures with parameter changes marked, as PNG bytes (pure matplotlib)."""

from __future__ import annotations

import io
from collections.abc import Sequence

__all__ = ["LiveSpeedFigure", "speed_png"]


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


class LiveSpeedFigure:
    """speed_png's picture for a live plot: one figure kept and redrawn (about 40 ms a redraw
    where building it anew takes about 100), laid out again and its marks redrawn only when
    they changed."""

    def __init__(self, *, title: str = "Robot speed from /odom") -> None:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        self.figure = Figure(figsize=(7, 3), dpi=90)
        FigureCanvasAgg(self.figure)
        self.axes = ax = self.figure.add_subplot()
        (self.line,) = ax.plot([], [], color="#1565c0", linewidth=1.8)
        ax.set_xlabel("simulated time (s)")
        ax.set_ylabel("speed (m/s)")
        ax.set_title(title)
        ax.grid(alpha=0.3)
        self._marks: list[tuple[float, str]] = []
        self._top = 0.0
        self._drawn: list[object] = []
        self._layout: tuple[object, ...] = ()

    def png(
        self, times: Sequence[float], speeds: Sequence[float], marks: Sequence[tuple[float, str]]
    ) -> bytes:
        """Return the PNG of these samples and marks (as speed_png draws them)."""
        ax = self.axes
        self.line.set_data(list(times), list(speeds))
        if times:
            ax.set_xlim(*_span(times[0], times[-1]))
        top = max([0.25, *speeds]) * 1.15
        if list(marks) != self._marks or top != self._top:
            for artist in self._drawn:
                artist.remove()  # type: ignore[attr-defined]
            self._drawn = []
            for t, label in marks:
                self._drawn.append(ax.axvline(t, color="#c62828", linestyle="--", linewidth=1))
                self._drawn.append(
                    ax.text(t, top * 0.97, f" {label}", color="#c62828", fontsize=8, va="top")
                )
            self._marks, self._top = list(marks), top
            ax.set_ylim(-0.02, top)
        low, high = ax.get_xlim()
        ticks = tuple(float(x) for x in ax.get_xticks() if low <= x <= high)
        layout = (ticks, self._top, len(self._marks))
        if layout != self._layout:  # the labels changed: lay the figure out again
            self.figure.tight_layout()
            self._layout = layout
        buffer = io.BytesIO()
        self.figure.savefig(buffer, format="png")
        return buffer.getvalue()


def _span(first: float, last: float) -> tuple[float, float]:
    """Return the x range matplotlib's autoscale gives a line from `first` to `last` (pure)."""
    margin = 0.05 * (last - first) if last > first else 0.5
    return first - margin, last + margin
