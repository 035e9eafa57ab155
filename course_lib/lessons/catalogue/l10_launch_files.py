"""Lesson 10, launch files: its self-check and its exercise's templated cells."""

from __future__ import annotations

from ...config.course import CourseSettings
from .shared import namesakes
from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC"]


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 10's checks: the launch set velocity 0.2, and every launch stopped."""
    seen = lesson.state.get("launch_velocities", [])
    launches = lesson.state.get("launches", [])
    stopped = bool(launches) and not any(handle.alive for handle in launches)
    # a node that has just stopped may be listed a moment more, and another lesson's (or a
    # terminal's) param_vel_node is not this lesson's launch: judge only what this one started
    listed, others = namesakes("/param_vel_node") if stopped else (True, [])
    what = "every launch was stopped (no param_vel_node left)"
    if listed and others:
        what += f" (the one running now is another: {', '.join(others)})"
    return [
        check("the Python launch file started param_vel_node with velocity 0.2", 0.2 in seen),
        check(
            what, stopped and (not listed or bool(others)), "run the cells that call `.stop()`."
        ),
    ]


def _launch_prose(s: CourseSettings) -> str:
    v = s.startup_exercises.launch_mps
    return (
        f"## Exercise\nWrite your own launch file that starts `param_vel_node` with velocity "
        f"**{v:g}**, and launch it. The check\nmeasures the robot's speed in the node's first "
        "seconds on `/odom`. Arm it (this needs the simulation):"
    )


def _launch_answer(s: CourseSettings) -> str:
    v = s.startup_exercises.launch_mps
    return (
        "%%writefile my_files/my_launch.launch.py\n"
        "from launch import LaunchDescription\n"
        "from launch_ros.actions import Node\n\n\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([\n"
        "        Node(\n"
        "            package='parameter_tests',\n"
        "            executable='param_vel',\n"
        "            name='param_vel_node',\n"
        f"            parameters=[{{'velocity': {v:g}}}],\n"
        "        )\n"
        "    ])"
    )


SPEC = LessonSpec(
    10,
    "10_launch_files.ipynb",
    "Launch files",
    self_check,
    driven_node="/param_vel_node",
    exercises=("10 launch file",),
    templates={"e10a0001": _launch_prose, "e10a0004": _launch_answer},
    settings=(
        "show_hints",
        "startup_exercises.launch_mps",
        "startup_exercises.tolerance_mps",
        "startup_exercises.window_s",
    ),
    world=True,
)
