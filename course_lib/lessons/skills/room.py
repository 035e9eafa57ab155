"""Room to drive before a measurement: a learner who reads for a while lets the robot drive on.

At 0.2 m/s the robot reaches the red box 2.25 m ahead of its start in about 11 s, and a
learner reads longer than that between setting `velocity` and running the cell that measures.
A measurement that needs more floor than is left ahead puts the robot back at its start pose
first (the node's velocity drives it again at once) and says so in one line; a measurement
that ends against an obstacle says what stopped it.
"""

from __future__ import annotations

from typing import Any

from ...config.floor import FLOOR_EDGE, Ahead, free_ahead, obstacle_words
from ...config.trip import VELOCITY_MAX_MPS
from ...sim.world.kinematics import Pose2D
from .measure import MOVING_MPS, distance_m

__all__ = ["SETTLE_S", "make_room", "met_on_the_way", "room_needed_m"]

SETTLE_S = 1.5  # simulated s a measurement may wait for the speed to settle before its window
_STOP_M = 0.05  # how far the robot rolls once its velocity drops to 0
_AGAINST_M = 0.02  # closer than this to an obstacle, the robot stands against it


def room_needed_m(velocity_mps: float, sim_seconds: float) -> float:
    """Return the floor (m) a drive of `sim_seconds` at `velocity_mps` needs, settling included.

    The robot tops out at VELOCITY_MAX_MPS whatever the node holds.
    """
    speed = min(abs(velocity_mps), VELOCITY_MAX_MPS)
    return round(speed * (sim_seconds + SETTLE_S) + _STOP_M, 2)


def _ahead(world: Any, reading: Any, velocity_mps: float, limit: float) -> Ahead:
    pose = reading.pose
    backwards = velocity_mps < 0
    return free_ahead(world.settings, pose.x, pose.y, pose.yaw, limit=limit, backwards=backwards)


def _words(world: Any, met: str | None) -> str:
    return FLOOR_EDGE if met == FLOOR_EDGE else obstacle_words(world.settings, met or "")


def make_room(world: Any, velocity_mps: float, sim_seconds: float) -> str:
    """Put the robot back at its start pose if the floor ahead is too short; say why.

    Returns the line to show, or "" when the robot had room (or stands still: nothing to do).
    """
    if abs(velocity_mps) < MOVING_MPS:
        return ""
    needed = room_needed_m(velocity_mps, sim_seconds)
    now = world.odom()
    ahead = _ahead(world, now, velocity_mps, needed)
    if ahead.blocker is None:
        return ""
    start = world.settings.start_pose
    driven = distance_m(Pose2D(start.x_m, start.y_m), now.pose)
    what = _words(world, ahead.blocker)
    world.reset()  # the node's next tick (0.1 s) drives it again at its velocity
    if ahead.free_m < _AGAINST_M:
        said = (
            f"While you read, the robot drove on at velocity {velocity_mps:g} and stood "
            f"against {what}, {driven:.1f} m from its start"
        )
    else:
        said = (
            f"The robot is {driven:.1f} m from its start, {ahead.free_m:.2f} m short of {what}; "
            f"{sim_seconds:g} s at velocity {velocity_mps:g} need {needed:.2f} m"
        )
    return f"{said}: it is back at its start pose, and velocity {velocity_mps:g} drives it again."


def met_on_the_way(world: Any, reading: Any, velocity_mps: float) -> str:
    """Return what the robot stands against at `reading` while its node drives it ("" if none)."""
    if abs(velocity_mps) < MOVING_MPS:
        return ""
    ahead = _ahead(world, reading, velocity_mps, _AGAINST_M)
    if ahead.blocker is None or ahead.free_m >= _AGAINST_M:
        return ""
    return _words(world, ahead.blocker)
