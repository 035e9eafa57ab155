"""What the robot did, from /odom, measured in simulated time (so the numbers are repeatable)."""

from __future__ import annotations

import math
from typing import Any

from .files import Text

__all__ = ["distance_m", "drive_report", "stop_report"]


def distance_m(a: Any, b: Any) -> float:
    """Return the straight-line distance between two poses (x, y in m)."""
    return math.hypot(b.x - a.x, b.y - a.y)


def drive_report(lesson: Any, sim_seconds: float) -> Text:
    """Let `sim_seconds` of simulated time pass; report the speed and distance from the start."""
    world = lesson.current_world
    now = world.odom()
    after = world.wait_sim_time(now.time_s + sim_seconds)
    start = world.settings.start_pose
    moved = math.hypot(after.pose.x - start.x_m, after.pose.y - start.y_m)
    lesson.state["top_speed"] = max(lesson.state.get("top_speed", 0.0), after.linear_mps)
    return Text(
        f"{sim_seconds:.1f} s of simulated time later: /odom says {after.linear_mps:.2f} m/s; "
        f"the robot is {moved:.1f} m from its start."
    )


def stop_report(lesson: Any, timeout: float = 10.0) -> Text:
    """Wait until /odom says the robot stands still; report it."""
    world = lesson.current_world
    reading = world.wait_for_odom(lambda r: abs(r.linear_mps) < 0.005, timeout)
    lesson.state["stopped"] = True
    return Text(f"The robot stopped: /odom says {abs(reading.linear_mps):.2f} m/s.")
