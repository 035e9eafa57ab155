"""What the robot did, from /odom, measured in simulated time (so the numbers are repeatable)."""

from __future__ import annotations

from typing import Any

from .files import Text
from .skills.measure import PARAM_ERRORS, distance_m, steady_odom

__all__ = ["distance_m", "drive_report", "steady_odom", "stop_report"]


START_WAIT_S = 5.0  # simulated s a still robot gets to start when its node holds a velocity


def _commanded_mps(lesson: Any) -> float:
    """Return the velocity that this lesson's running param_vel_node holds (0.0 if none)."""
    from ..ros2.api import nodes_and_params as api

    child = lesson.started.get("param_vel")
    if child is None or not child.alive:
        return 0.0
    try:
        return float(api.param_get("/param_vel_node", "velocity").value)
    except PARAM_ERRORS:
        return 0.0


def drive_report(lesson: Any, sim_seconds: float) -> Text:
    """Let `sim_seconds` of simulated time pass; report the speed and the distance driven.

    Both numbers are measured on this lesson's robot during this call only, so nothing from
    before (another lesson's drive, an earlier run) can make them look right.
    """
    world = lesson.current_world
    # a velocity set just before on a node started moments ago reaches the robot once the
    # simulation has discovered the node's /cmd_vel publisher: on a busy host, over 1 s later
    patient = _commanded_mps(lesson) != 0.0
    before = steady_odom(world, still_wait_s=START_WAIT_S if patient else 1.0)
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
