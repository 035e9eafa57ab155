"""Lesson 3, the simulation: the MuJoCo world runs and the robot's topics exist."""

from __future__ import annotations

from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC"]


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 3's checks: the world runs, /cmd_vel, /odom and /scan exist."""
    from ...ros2.api import nodes_and_params as api

    world = lesson.attached_world
    alive = world is not None and world.alive
    topics = {t.name for t in api.topic_list()} if alive else set()
    return [
        check("the simulation is running", alive, "run the cell with `lesson.world()`."),
        check(
            "the robot's topics /cmd_vel, /odom and /scan exist",
            {"/cmd_vel", "/odom", "/scan"} <= topics,
            "start the world, then list topics again.",
        ),
    ]


SPEC = LessonSpec(3, "03_the_simulation.ipynb", "The simulation", self_check, world=True)
