"""Lesson 11, beyond the tutorial: descriptors, the panel, and two exercises' templated cells."""

from __future__ import annotations

from typing import Any

from ...config.course import CourseSettings
from ...config.trip import answer_trip, wrong_trip
from .shared import cm, only_driver, other_drivers
from .spec import Check, LessonSpec, LessonView, check

__all__ = ["NODE", "SPEC"]

NODE = "descriptor_vel_node"


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 11's checks: the range, read-only, the saved panel, the exercise."""
    from ...core.errors import CourseError
    from ...ros2.api import nodes_and_params as api

    rejected: Any
    read_only: Any
    try:  # both must be refused by the running node itself, not fail for its absence
        rejected = api.param_set("/descriptor_vel_node", "velocity", 0.3)
        read_only = api.param_set("/descriptor_vel_node", "max_travel", 9.0)
    except CourseError:
        rejected = read_only = None
    running = "run the `%ros2 run parameter_descriptors descriptor_vel` cell."
    saved = lesson.state.get("saved_params")
    return [
        only_driver(lesson, "descriptor_vel", NODE, other_drivers(lesson, "descriptor_vel")),
        check(
            "the range refuses velocity 0.3 (max 0.26)",
            rejected is not None and not rejected.successful,
            running,
        ),
        check("max_travel is read-only", read_only is not None and not read_only.successful),
        check(
            "the panel saved a params file ROS can load",
            saved is not None and saved.exists(),
            "press the panel's save button (or run `panel.save(...)`).",
        ),
        check(
            "the travel exercise passed",
            lesson.state.get("exercise_passed", False),
            "change the two numbers of the exercise cell and run it and the check again.",
        ),
    ]


def _task_prose(s: CourseSettings) -> str:
    task = s.travel_exercise
    return (
        f"## Exercise\nMake the robot travel **{task.target_m:.2f} m** (within "
        f"{cm(task.tolerance_m)}) and stop, using parameters only. Setting `velocity`\n"
        "starts a trip; the node stops by itself after `travel_time` simulated seconds.\n\n"
        "First, put the robot at its start and arm the checker:"
    )


def _trip_cell(travel_time: float, velocity: float) -> str:
    return (
        "%%ros2\n"
        f"param set /descriptor_vel_node travel_time {travel_time:.1f}\n"
        f"param set /descriptor_vel_node velocity {velocity:g}"
    )


def _answer(s: CourseSettings) -> Any:
    task = s.travel_exercise
    trip = answer_trip(task.target_m, task.tolerance_m, s.default_velocity_mps)
    if trip is None:  # make check-config refuses such a course.yaml before anything runs
        raise ValueError(f"no answer reaches {task.target_m} m: run `make check-config`")
    return trip


def _wrong_cell(s: CourseSettings) -> str:
    wrong = wrong_trip(_answer(s))
    return _trip_cell(wrong.travel_time_s, wrong.velocity_mps)


def _answer_cell(s: CourseSettings) -> str:
    answer = _answer(s)
    return _trip_cell(answer.travel_time_s, answer.velocity_mps)


def _saved_panel_prose(s: CourseSettings) -> str:
    t = s.startup_exercises.saved_panel_travel_s
    v = s.default_velocity_mps
    return (
        f"## Exercise: a saved value survives a restart\nWith the panel, set `travel_time` to "
        f"**{t:.1f}** and save. Then restart `descriptor_vel_node` so that it keeps the value.\n"
        f"The check sets velocity {v:g} and measures the trip on `/odom`. Arm it:"
    )


def _saved_panel_answer(s: CourseSettings) -> str:
    t = s.startup_exercises.saved_panel_travel_s
    return f'panel.controls["travel_time"].value = {t:.1f}  # what moving the slider does'


SPEC = LessonSpec(
    11,
    "11_beyond_the_tutorial.ipynb",
    "Beyond the tutorial",
    self_check,
    driven_node="/descriptor_vel_node",
    exercises=("11 saved panel", "11 travel"),
    templates={
        "050bc758": _task_prose,
        "2459711a": _wrong_cell,
        "a8e1d8cf": _answer_cell,
        "e11a0001": _saved_panel_prose,
        "e11a0003": _saved_panel_answer,
    },
    settings=(
        "default_velocity_mps",
        "show_hints",
        "travel_exercise.target_m",
        "travel_exercise.tolerance_m",
        "travel_exercise.timeout_s",
        "startup_exercises.saved_panel_travel_s",
        "startup_exercises.travel_tolerance_s",
    ),
    world=True,
)
