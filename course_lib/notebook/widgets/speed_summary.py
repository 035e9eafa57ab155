"""The speed plot in words, for a screen reader (the SVG's <desc>): what each marked change did
to the robot's speed, from the samples themselves (pure: no ROS).

"velocity was set to 0.2 at 1.0 s: speed rose from 0.00 to 0.20 m/s by 1.4 s."
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from ...viz.speed_svg import latest_run

__all__ = ["speed_summary"]

STEADY_MPS = 0.005  # a change of speed smaller than this is "stayed"
SETTLED = 0.05  # "by" when the speed is within this share of the change from where it ended
_SET = re.compile(r"^(?:#\d+ )?(?P<name>\S+) := (?P<value>.+)$")


def _mps(speed: float) -> str:
    """Return a speed in m/s to the centimetre per second, never '-0.00'."""
    return f"{round(speed, 2) + 0.0:.2f}"


def _what(label: str) -> str:
    """Return a mark's label as words: '#3 velocity := 0.2' -> 'velocity was set to 0.2'."""
    found = _SET.match(label)
    return f"{found['name']} was set to {found['value']}" if found else label


def _level(run: list[tuple[float, float]], stamp: float) -> float:
    """Return the speed of the last sample at or before `stamp` (the first, before any)."""
    before = [v for t, v in run if t <= stamp]
    return before[-1] if before else run[0][1]


def _after(run: list[tuple[float, float]], stamp: float, end: float, what: str) -> str:
    """Return what the speed did between a mark at `stamp` and the next mark at `end`."""
    start = _level(run, stamp)
    segment = [(t, v) for t, v in run if stamp < t < end]
    if not segment:
        return f"{what} at {stamp:.1f} s."
    final = segment[-1][1]
    change = final - start
    if abs(change) < STEADY_MPS:
        return f"{what} at {stamp:.1f} s: speed stayed at {_mps(final)} m/s."
    near = max(STEADY_MPS, abs(change) * SETTLED)
    reached = next(t for t, v in segment if abs(v - final) <= near)
    verb = "rose" if change > 0 else "fell"
    return (
        f"{what} at {stamp:.1f} s: speed {verb} from {_mps(start)} to {_mps(final)} m/s "
        f"by {reached:.1f} s."
    )


def speed_summary(
    samples: Sequence[tuple[float, float]], marks: Sequence[tuple[float, str]]
) -> str:
    """Return a few sentences saying what the plot of `samples` (sim time s, m/s) with `marks`
    (sim time s, label) shows: the time span, each mark's effect on the speed, the top speed."""
    run = latest_run(samples)
    if not run:
        return "No speed sample yet."
    t0, t1 = run[0][0], run[-1][0]
    shown = sorted((t, label) for t, label in marks if t0 - 1e-6 <= t <= t1 + 1e-6)
    said = [f"Simulated time {t0:.1f} to {t1:.1f} s."]
    for index, (stamp, label) in enumerate(shown):
        end = shown[index + 1][0] if index + 1 < len(shown) else t1 + 1.0
        said.append(_after(run, stamp, end, _what(label)))
    speeds = [v for _, v in run]
    if not shown:
        said.append(f"Speed from {_mps(min(speeds))} to {_mps(max(speeds))} m/s.")
    said.append(f"Top speed {_mps(max(speeds))} m/s; last {_mps(speeds[-1])} m/s.")
    return " ".join(said)
