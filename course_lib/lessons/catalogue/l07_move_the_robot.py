"""Lesson 7, move the robot with a parameter: its self-check and its templated cells."""

from __future__ import annotations

from ...config.course import CourseSettings
from ...config.trip import VELOCITY_MAX_MPS
from .shared import cm, only_driver, other_drivers, own_node_running, velocity
from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC"]


def _standing_still(lesson: LessonView) -> bool:
    """Return True if this lesson's robot stands still now (measured on /odom)."""
    world = lesson.attached_world
    return world is not None and world.alive and abs(world.odom().linear_mps) < 0.005


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 7's checks: the only driver, the speed reached, stopped again."""
    others = other_drivers(lesson, "param_vel")
    alone = only_driver(lesson, "param_vel", "param_vel_node", others)
    if others:  # the robot's motion is not only the learner's doing: judge nothing of it
        return [alone]
    target = lesson.velocity
    top = lesson.state.get("top_speed", 0.0)  # measured by this lesson's drive_for()
    return [
        alone,
        check(
            f"the robot drove at {target:g} m/s (measured on /odom)",
            abs(top - target) < 0.02,
            f"set velocity to {target:g}, then run the cell that waits in simulated time.",
        ),
        check(
            "velocity is back to 0.0 and the robot stopped",
            own_node_running(lesson) and velocity() == 0.0 and _standing_still(lesson),
            "`%ros2 param set /param_vel_node velocity 0.0`, then the cell after it.",
        ),
    ]


def _set_velocity_prose(s: CourseSettings) -> str:
    v = s.default_velocity_mps
    if round(v, 2) == 0.2:
        return (
            "Now set the velocity, exactly as in the tutorial, and look at the 3D view "
            "and the plot:"
        )
    return (
        f"Now set the velocity to {v:g} m/s (the tutorial uses 0.2; this course drives at "
        f"{v:g}), and look at the 3D view and the plot:"
    )


def _set_velocity(s: CourseSettings) -> str:
    return f"%ros2 param set /param_vel_node velocity {s.default_velocity_mps:g}"


def _drive_prose(s: CourseSettings) -> str:
    task = s.drive_exercise
    return (
        f"## Exercise\nMake the robot drive **{task.distance_m:g} m in {task.time_s:g} s** "
        f"(within {cm(task.tolerance_m)}) by setting `velocity` while the node runs. The check\n"
        f"measures the next {task.time_s:g} s of simulated time, then stops the robot (which tops "
        f"out at {VELOCITY_MAX_MPS:g} m/s). A wrong attempt gets a hint, more specific each "
        "time.\n\nFirst, put the robot at its start and arm the checker:"
    )


def _drive_answer(s: CourseSettings) -> str:
    task = s.drive_exercise
    return f"%ros2 param set /param_vel_node velocity {round(task.distance_m / task.time_s, 3):g}"


SPEC = LessonSpec(
    7,
    "07_move_the_robot.ipynb",
    "Move the robot with a parameter",
    self_check,
    driven_node="/param_vel_node",
    exercises=("07 drive",),
    templates={
        "565b596f": _set_velocity_prose,
        "0d2c3bb5": _set_velocity,
        "e7d1a001": _drive_prose,
        "e7d1a003": _drive_answer,
    },
    settings=(
        "default_velocity_mps",
        "show_hints",
        "drive_exercise.distance_m",
        "drive_exercise.time_s",
        "drive_exercise.tolerance_m",
    ),
    world=True,
)
