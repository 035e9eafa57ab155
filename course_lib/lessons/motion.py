"""What the robot did, from /odom, measured in simulated time (so the numbers are repeatable)."""

from __future__ import annotations

from typing import Any

from .files import Text
from .skills.measure import distance_m, steady_odom

__all__ = ["distance_m", "drive_report", "steady_odom", "stop_report"]


def drive_report(lesson: Any, sim_seconds: float) -> Text:
    """Let `sim_seconds` of simulated time pass; report the speed and the distance driven.

    Both numbers are measured on this lesson's robot during this call only, so nothing from
    before (another lesson's drive, an earlier run) can make them look right.
    """
    world = lesson.current_world
    before = steady_odom(world)
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
