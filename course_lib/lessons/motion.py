"""What the robot did, from /odom, measured in simulated time (so the numbers are repeatable)."""

from __future__ import annotations

from typing import Any

from .files import Text
from .skills.measure import PARAM_ERRORS, distance_m, steady_odom
from .skills.room import make_room, met_on_the_way

__all__ = ["distance_m", "drive_report", "steady_odom", "stop_report"]


START_WAIT_S = 5.0  # simulated s a still robot gets to start when its node holds a velocity


def _commanded_mps(lesson: Any) -> float:
    """Return the velocity that this lesson's running param_vel_node holds (0.0 if none)."""
    from ..ros2.api import nodes_and_params as api
    from .catalogue.shared import (
        own_node,
    )  # the `%ros2 run` cell's process as well as lesson.run's

    child = own_node(lesson)
    if child is None or not child.alive:
        return 0.0
    try:
        return float(api.param_get("/param_vel_node", "velocity").value)
    except PARAM_ERRORS:
        return 0.0


def drive_report(lesson: Any, sim_seconds: float) -> Text:
    """Let `sim_seconds` of simulated time pass; report the speed and the distance driven.

    Both numbers are measured on this lesson's robot during this call only, so nothing from
    before (another lesson's drive, an earlier run) can make them look right. A robot that
    drove on while the learner read and has no room left ahead is put back at its start pose
    first, and the report says so.
    """
    world = lesson.current_world
    commanded = _commanded_mps(lesson)
    moved_back = make_room(world, commanded, sim_seconds)
    if moved_back:
        print(moved_back)
    print(f"Measuring {sim_seconds:g} s of simulated time on /odom ...", flush=True)
    # a velocity set just before on a node started moments ago reaches the robot once the
    # simulation has discovered the node's /cmd_vel publisher: on a busy host, over 1 s later
    before = steady_odom(world, still_wait_s=START_WAIT_S if commanded != 0.0 else 1.0)
    after = world.wait_sim_time(before.time_s + sim_seconds)
    driven = distance_m(before.pose, after.pose)
    lesson.state["top_speed"] = max(lesson.state.get("top_speed", 0.0), after.linear_mps)
    said = (
        f"{sim_seconds:.1f} s of simulated time later: /odom says {after.linear_mps:.2f} m/s; "
        f"the robot drove {driven:.1f} m in that time."
    )
    against = met_on_the_way(world, after, commanded)
    if against:
        said += f" It stands against {against}: the floor ahead was too short for this drive."
    return Text(said)


def stop_report(lesson: Any, timeout: float = 10.0) -> Text:
    """Wait until /odom says the robot stands still; report it."""
    world = lesson.current_world
    reading = world.wait_for_odom(lambda r: abs(r.linear_mps) < 0.005, timeout)
    return Text(f"The robot stopped: /odom says {abs(reading.linear_mps):.2f} m/s.")
