"""Lesson 2, key points: parameters live in nodes (and go when their node stops)."""

from __future__ import annotations

from .shared import namesakes, own_node, own_node_running
from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC"]


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 2's checks: param_vel_node started here, then stopped."""
    started = own_node(lesson) is not None
    gone = started and not own_node_running(lesson)
    listed, others = namesakes("/param_vel_node") if gone else (False, [])
    what = "param_vel_node is gone, and its parameters with it"
    if listed and others:  # yours is gone; another lesson's or a terminal's has the name
        what += f" (the one running now is another: {', '.join(others)}, with its own)"
    return [
        check(
            "you started param_vel_node in this lesson",
            started,
            "run the `%ros2 run parameter_tests param_vel` cell.",
        ),
        check(
            what,
            gone and (not listed or bool(others)),
            'run the cell with `lesson.stop("param_vel")`.',
        ),
    ]


SPEC = LessonSpec(
    2,
    "02_key_points.ipynb",
    "Key points: parameters live in nodes",
    self_check,
    # a mistake's hint under Jazzy's text (notebook/hints.py): a stopped node, a typo, a file
    settings=("show_hints",),
)
