"""Lesson 4, the parameter_tests package: the node declares `velocity` and publishes it."""

from __future__ import annotations

import re

from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC"]


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 4's checks of the installed node's source."""
    from ...core import ament
    from ...core.errors import CourseError
    from ...launch.ros.declared import declared_parameters, node_sources

    try:  # the installed node the learner runs, not the file they may be editing
        exe = str(ament.find_executable("parameter_tests", "param_vel", lesson.session.env))
    except CourseError:
        exe = ""
    velocity = declared_parameters(exe).get("velocity") if exe else None
    sources = node_sources(exe) if exe else []
    source = sources[0].read_text(encoding="utf-8") if sources else ""
    return [
        check(
            "the node declares `velocity` as a double, default 0.0",
            velocity is not None and velocity.type == "double" and velocity.default == 0.0,
            "compare the declare_parameter line with the tutorial's; then `make setup`.",
        ),
        check("a 0.1 s timer publishes it", re.search(r"create_timer\(0\.1,", source) is not None),
    ]


SPEC = LessonSpec(
    4, "04_the_parameter_tests_package.ipynb", "The parameter_tests package", self_check
)
