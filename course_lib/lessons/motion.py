"""What the robot did, from /odom, measured in simulated time (so the numbers are repeatable)."""

from __future__ import annotations

import math
from typing import Any

from .files import Text

__all__ = ["distance_m", "drive_report", "steady_odom", "stop_report"]

_STEADY_S = 0.2  # simulated seconds between the readings compared
_SPEED_TOLERANCE = 0.002  # m/s


def distance_m(a: Any, b: Any) -> float:
    """Return the straight-line distance between two poses (x, y in m)."""
    return math.hypot(b.x - a.x, b.y - a.y)


def _steady(world: Any, *, still_wait_s: float = 1.0) -> Any:
    """Return the first /odom reading after the robot's speed stopped changing.

    A speed change set just before (the node acts on its next 0.1 s tick) is let through
    first, so the window that follows measures the drive, not the start; a robot standing
    still gets `still_wait_s` of simulated time to start moving.
    """
    first = previous = world.odom()
    while True:
        reading = world.wait_sim_time(previous.time_s + _STEADY_S)
        steady = abs(reading.linear_mps - previous.linear_mps) < _SPEED_TOLERANCE
        moving = abs(reading.linear_mps) >= _SPEED_TOLERANCE
        waited = reading.time_s - first.time_s
        if (steady and (moving or waited >= still_wait_s)) or waited >= 5.0:
            return reading
        previous = reading


def steady_odom(world: Any) -> Any:
    """Return the first /odom reading after the robot's speed stopped changing."""
    return _steady(world)


def drive_report(lesson: Any, sim_seconds: float) -> Text:
    """Let `sim_seconds` of simulated time pass; report the speed and the distance driven.

    Both numbers are measured on this lesson's robot during this call only, so nothing from
    before (another lesson's drive, an earlier run) can make them look right.
    """
    world = lesson.current_world
    before = _steady(world)
    after = world.wait_sim_time(before.time_s + sim_seconds)
    driven = distance_m(before.pose, after.pose)
    lesson.state["top_speed"] = max(lesson.state.get("top_speed", 0.0), after.linear_mps)
    return Text(
        f"{sim_seconds:.1f} s of simulated time later: /odom says {after.linear_mps:.2f} m/s; "
        f"the robot drove {driven:.1f} m in that time."
    )


def stop_report(lesson: Any, timeout: float = 10.0) -> Text:
    """Wait until /odom says the robot stands still; report it."""
    world = lesson.current_world
    reading = world.wait_for_odom(lambda r: abs(r.linear_mps) < 0.005, timeout)
    return Text(f"The robot stopped: /odom says {abs(reading.linear_mps):.2f} m/s.")
