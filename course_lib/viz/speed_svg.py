"""A replay's speed plot as inline SVG: speed over simulated time, parameter changes marked.

The replay page draws it without any script, font or network resource; the same samples and
marks always give the same bytes (fixed number formats, a fixed point budget).
"""

from __future__ import annotations

import html
from collections.abc import Sequence

__all__ = ["PLAYHEAD_ID", "PLOT_ID", "latest_run", "speed_svg"]

PLOT_ID = "speed-plot"
PLAYHEAD_ID = "playhead"
MAX_POINTS = 1500  # a long run is thinned to this many points (evenly, deterministically)
_W, _H = 760, 230
_LEFT, _RIGHT, _TOP, _BOTTOM = 52, 16, 26, 34
_LINE, _MARK = "#1565c0", "#c62828"


def latest_run(samples: Sequence[tuple[float, float]]) -> list[tuple[float, float]]:
    """Return the samples after the last time simulated time went back (a world restart)."""
    start = 0
    for i in range(1, len(samples)):
        if samples[i][0] < samples[i - 1][0]:
            start = i
    return list(samples[start:])


def _ticks(low: float, high: float, count: int = 5) -> list[float]:
    """Return round tick values covering [low, high]."""
    span = max(high - low, 1e-9)
    raw = span / count
    step = min(s * 10.0**e for e in range(-3, 5) for s in (1, 2, 5) if s * 10.0**e >= raw)
    first = -(-low // step) * step
    out, value = [], first
    while value <= high + 1e-9:
        out.append(round(value, 6) + 0.0)  # + 0.0: never a '-0' label
        value += step
    return out


def _thin(samples: list[tuple[float, float]]) -> list[tuple[float, float]]:
    if len(samples) <= MAX_POINTS:
        return samples
    stride = len(samples) / MAX_POINTS
    return [samples[int(i * stride)] for i in range(MAX_POINTS)] + [samples[-1]]


def speed_svg(
    samples: Sequence[tuple[float, float]],
    marks: Sequence[tuple[float, str]],
    *,
    title: str = "Robot speed from /odom",
    summary: str = "",
) -> str:
    """Return an SVG of (sim time s, speed m/s) samples with a numbered dashed line per mark.

    Marks outside the samples' time span are left out; a legend under the plot lists each
    numbered mark with its simulated time and label. A screen reader announces a picture
    (role img) named by `title` and described by `summary` (what the plot shows, in words).
    """
    run = latest_run(samples)
    if run:
        t0, t1 = run[0][0], max(run[-1][0], run[0][0] + 1.0)
    else:
        t0, t1 = 0.0, 1.0
    shown = [(t, label) for t, label in marks if run and t0 - 1e-6 <= t <= t1 + 1e-6]
    top = max([0.25, *(abs(v) for _, v in run)]) * 1.15
    low = min([0.0, *(v for _, v in run)]) * 1.15
    width, height = _W - _LEFT - _RIGHT, _H - _TOP - _BOTTOM

    def x(t: float) -> float:
        return _LEFT + (t - t0) / (t1 - t0) * width

    def y(v: float) -> float:
        return _TOP + (top - v) / (top - low) * height

    legend_h = 18 * len(shown) + (8 if shown else 0)
    parts = [
        f'<svg id="{PLOT_ID}" width="{_W}" '
        f'height="{_H + legend_h}" viewBox="0 0 {_W} {_H + legend_h}" '
        f'data-t0="{t0:.4f}" data-t1="{t1:.4f}" data-x0="{_LEFT}" data-width="{width}" '
        'font-family="sans-serif" font-size="12" role="img">',
        f"<title>{html.escape(title)}</title>",
        *([f"<desc>{html.escape(summary)}</desc>"] if summary else []),
        f'<text x="{_W / 2:.0f}" y="16" text-anchor="middle" font-size="14">'
        f"{html.escape(title)}</text>",
        f'<rect x="{_LEFT}" y="{_TOP}" width="{width}" height="{height}" fill="none" '
        'stroke="#999"/>',
    ]
    for v in _ticks(low, top):
        parts.append(
            f'<line x1="{_LEFT}" x2="{_LEFT + width}" y1="{y(v):.1f}" y2="{y(v):.1f}" '
            'stroke="#ddd"/>'
            f'<text x="{_LEFT - 6}" y="{y(v) + 4:.1f}" text-anchor="end">{v:g}</text>'
        )
    for t in _ticks(t0, t1):
        parts.append(
            f'<text x="{x(t):.1f}" y="{_TOP + height + 16}" text-anchor="middle">{t:g}</text>'
        )
    parts.append(
        f'<text x="{_LEFT + width / 2:.0f}" y="{_H - 3}" text-anchor="middle">'
        "simulated time (s)</text>"
        f'<text x="14" y="{_TOP + height / 2:.0f}" text-anchor="middle" '
        f'transform="rotate(-90 14 {_TOP + height / 2:.0f})">speed (m/s)</text>'
    )
    if run:
        points = " ".join(f"{x(t):.1f},{y(v):.1f}" for t, v in _thin(run))
        parts.append(
            f'<polyline class="speed" fill="none" stroke="{_LINE}" stroke-width="1.8" '
            f'points="{points}"/>'
        )
    for number, (t, label) in enumerate(shown, 1):
        parts.append(
            f'<g class="mark" data-time="{t:.3f}"><line x1="{x(t):.1f}" x2="{x(t):.1f}" '
            f'y1="{_TOP}" y2="{_TOP + height}" stroke="{_MARK}" stroke-dasharray="5,3"/>'
            f'<text x="{x(t) + 3:.1f}" y="{_TOP + 12}" fill="{_MARK}">{number}</text></g>'
        )
        parts.append(
            f'<text class="legend" x="{_LEFT}" y="{_H + 14 + 18 * (number - 1)}" '
            f'fill="{_MARK}">{number} · {t:.1f} s · {html.escape(label)}</text>'
        )
    parts.append(
        f'<line id="{PLAYHEAD_ID}" x1="{_LEFT}" x2="{_LEFT}" y1="{_TOP}" '
        f'y2="{_TOP + height}" stroke="#2e7d32" stroke-width="2" visibility="hidden"/>'
    )
    parts.append("</svg>")
    return "\n".join(parts)
