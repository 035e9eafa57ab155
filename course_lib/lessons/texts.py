"""The lesson cells that state a configured value, rendered from config/course.yaml (pure).

A learner reads and types literal numbers, as in the ROS 2 tutorial and as a terminal needs
them (`velocity 0.2`, not an expression); an instructor changes course.yaml and runs
`make notebooks`, which renders these cells (found by their cell id) before executing the
lesson, so prose, commands and stored outputs all show the configured values. Each rendered
notebook records the settings it was made with (`metadata.course_settings`), so
`make check-config` can say which lessons still show other values. Edit a templated cell here,
not in the notebook: `make notebooks` would put this text back.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..config.course import CourseSettings
from ..config.trip import VELOCITY_MAX_MPS, answer_trip, wrong_trip

__all__ = ["METADATA_KEY", "TEMPLATES", "render_cells", "settings_used", "stale_notebooks"]

METADATA_KEY = "course_settings"
Template = Callable[[CourseSettings], str]


def _cm(metres: float) -> str:
    return f"{metres * 100:g} cm"


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


def _task_prose(s: CourseSettings) -> str:
    task = s.travel_exercise
    return (
        f"## Exercise\nMake the robot travel **{task.target_m:.2f} m** (within "
        f"{_cm(task.tolerance_m)}) and stop, using parameters only. Setting `velocity`\n"
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


def _drive_prose(s: CourseSettings) -> str:
    task = s.drive_exercise
    return (
        f"## Exercise\nMake the robot drive **{task.distance_m:g} m in {task.time_s:g} s** "
        f"(within {_cm(task.tolerance_m)}) by setting `velocity` while the node runs. The check\n"
        f"measures the next {task.time_s:g} s of simulated time, then stops the robot (which tops "
        f"out at {VELOCITY_MAX_MPS:g} m/s). A wrong attempt gets a hint, more specific each "
        "time.\n\nFirst, put the robot at its start and arm the checker:"
    )


def _drive_answer(s: CourseSettings) -> str:
    task = s.drive_exercise
    return f"%ros2 param set /param_vel_node velocity {round(task.distance_m / task.time_s, 3):g}"


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


# notebook file name -> cell id -> template
TEMPLATES: dict[str, dict[str, Template]] = {
    "07_move_the_robot.ipynb": {
        "565b596f": _set_velocity_prose,
        "0d2c3bb5": lambda s: (
            f"%ros2 param set /param_vel_node velocity {s.default_velocity_mps:g}"
        ),
        "e7d1a001": _drive_prose,
        "e7d1a003": _drive_answer,
    },
    "09_load_yaml_at_startup.ipynb": {
        "e9d1a001": _params_file_prose,
        "e9d1a005": _params_file_answer,
    },
    "10_launch_files.ipynb": {
        "e10a0001": _launch_prose,
        "e10a0004": _launch_answer,
    },
    "11_beyond_the_tutorial.ipynb": {
        "050bc758": _task_prose,
        "2459711a": _wrong_cell,
        "a8e1d8cf": _answer_cell,
        "e11a0001": _saved_panel_prose,
        "e11a0003": _saved_panel_answer,
    },
}

# notebook file name -> the settings its cells and outputs depend on
_USED: dict[str, tuple[str, ...]] = {
    # a mistake's hint under Jazzy's text (notebook/hints.py): a stopped node, a typo, a file
    "02_key_points.ipynb": ("show_hints",),
    "06_check_parameters.ipynb": ("show_hints",),
    "07_move_the_robot.ipynb": (
        "default_velocity_mps",
        "show_hints",
        "drive_exercise.distance_m",
        "drive_exercise.time_s",
        "drive_exercise.tolerance_m",
    ),
    "09_load_yaml_at_startup.ipynb": (
        "show_hints",
        "startup_exercises.params_file_mps",
        "startup_exercises.tolerance_mps",
        "startup_exercises.window_s",
    ),
    "10_launch_files.ipynb": (
        "show_hints",
        "startup_exercises.launch_mps",
        "startup_exercises.tolerance_mps",
        "startup_exercises.window_s",
    ),
    "11_beyond_the_tutorial.ipynb": (
        "default_velocity_mps",
        "show_hints",
        "travel_exercise.target_m",
        "travel_exercise.tolerance_m",
        "travel_exercise.timeout_s",
        "startup_exercises.saved_panel_travel_s",
        "startup_exercises.travel_tolerance_s",
    ),
}


def settings_used(name: str, settings: CourseSettings) -> dict[str, Any]:
    """Return the settings notebook `name` depends on, by dotted key ({} for none)."""
    found: dict[str, Any] = {}
    for key in _USED.get(name, ()):
        value: Any = settings
        for part in key.split("."):
            value = getattr(value, part)
        found[key] = value
    return found


def render_cells(name: str, nb: Any, settings: CourseSettings) -> list[str]:
    """Render notebook `name`'s templated cells into `nb` (nbformat); return the changed ids."""
    templates = TEMPLATES.get(name, {})
    changed = []
    for cell in nb.cells:
        template = templates.get(cell.get("id"))
        if template is not None and cell.source != template(settings):
            cell.source = template(settings)
            changed.append(cell.id)
    missing = set(templates) - {c.get("id") for c in nb.cells}
    if missing:
        raise ValueError(f"{name} has no cell {sorted(missing)[0]}: update lessons/texts.py")
    used = settings_used(name, settings)
    if used:
        nb.metadata[METADATA_KEY] = used
    return changed


def stale_notebooks(folder: Path, settings: CourseSettings) -> list[str]:
    """Return a line for each notebook in `folder` made with other settings than `settings`."""
    import json

    lines = []
    for name in sorted(_USED):
        path = folder / name
        if not path.exists():
            continue
        nb = json.loads(path.read_text(encoding="utf-8"))
        made = nb.get("metadata", {}).get(METADATA_KEY, {})
        now = settings_used(name, settings)
        differ = [f"{k} {made.get(k)!r} (now {v!r})" for k, v in now.items() if made.get(k) != v]
        if differ:
            lines.append(
                f"notebooks/{name} shows the values of other settings: {', '.join(differ)}; "
                f"run `make notebooks ARGS={name}` to render and re-execute it."
            )
    return lines
