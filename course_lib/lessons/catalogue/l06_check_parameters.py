"""Lesson 6, check parameters: the running node answers for its velocity."""

from __future__ import annotations

from .shared import own_node_running, velocity
from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC"]


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 6's check: the node started here answers velocity 0.0."""
    return [
        check(
            "param_vel_node, started in this lesson, answers: velocity is 0.0",
            own_node_running(lesson) and velocity() == 0.0,
            "start it with `%ros2 run parameter_tests param_vel`.",
        ),
    ]


SPEC = LessonSpec(
    6,
    "06_check_parameters.ipynb",
    "Check parameters",
    self_check,
    settings=("show_hints",),
    world=True,
)
