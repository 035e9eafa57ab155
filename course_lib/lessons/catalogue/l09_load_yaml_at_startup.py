"""Lesson 9, load a YAML file at start-up: its self-check and its exercise's templated cells."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ...config.course import CourseSettings
from .shared import written_in
from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC"]


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 9's checks: the edited params file, and what a launch with it starts."""
    from ...launch.command.dry_run import dry_run

    path = lesson.learner_file("param_vel_node.yaml")
    value = _file_velocity(path) if written_in(lesson, path) else None
    return [
        check(
            "your params file sets velocity: 0.3 (a double)",
            value == 0.3 and type(value) is float,
            "run the cells that copy and edit the file.",
        ),
        check(
            "a launch with it would start param_vel_node with velocity 0.3",
            value == 0.3 and _planned_velocity(dry_run, path) == 0.3,
            "run the cells that copy and edit the file.",
        ),
    ]


def _file_velocity(path: Path) -> Any:
    """Return the velocity the file gives /param_vel_node as rcl reads it (its sections that
    select the node, the last one winning), or None."""
    import yaml

    from ...ros2.paramfile import load_params_text, sections_for

    try:
        data = load_params_text(path.read_text(encoding="utf-8"), name=str(path))
    except (OSError, yaml.YAMLError, ValueError):  # ValueError: an alias bomb, refused
        return None
    given = [
        s.params["velocity"]
        for s in sections_for(data, "/param_vel_node")
        if isinstance(s.params, dict) and "velocity" in s.params
    ]
    return given[-1] if given else None


def _planned_velocity(dry_run: Any, path: Any) -> Any:
    try:
        report = dry_run(
            "parameter_tests", "test_parameters_file.launch.py", f"params_file:={path}"
        )
    except Exception:
        return None
    return report.nodes[0].values.get("velocity", (None,))[0] if report.nodes else None


def _params_file_prose(s: CourseSettings) -> str:
    v = s.startup_exercises.params_file_mps
    return (
        f"## Exercise\nMake `param_vel_node` start at **{v:g} m/s**, from its first second: "
        "dump its parameters to a file, edit the file, and restart the node with "
        "`--params-file`.\nThe check measures the robot's speed in the node's first seconds "
        "on `/odom`. Arm it (this needs the simulation):"
    )


def _params_file_answer(s: CourseSettings) -> str:
    v = s.startup_exercises.params_file_mps
    return f'lesson.edit_file("my_files/start_fast.yaml", "velocity: 0.0", "velocity: {v:g}")'


SPEC = LessonSpec(
    9,
    "09_load_yaml_at_startup.ipynb",
    "Load a YAML file at start-up",
    self_check,
    driven_node="/param_vel_node",
    exercises=("09 params file",),
    templates={"e9d1a001": _params_file_prose, "e9d1a005": _params_file_answer},
    settings=(
        "show_hints",
        "startup_exercises.params_file_mps",
        "startup_exercises.tolerance_mps",
        "startup_exercises.window_s",
    ),
    world=True,
)
