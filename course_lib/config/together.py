"""Check the instructor's files against each other: the lessons must be doable in the world.

Pure geometry on the floor plane (no MuJoCo): the robot's footprint at its start pose must be
on the floor and clear of every obstacle, and the straight drives of lessons 7 and 11 (the
robot goes straight ahead from its start pose) must stay clear too; lesson 11's target must be
reachable with the velocities and travel times `descriptor_vel_node` accepts.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import yaml

from ..core.errors import ConfigError
from .course import CourseSettings, course_yaml, load_course_settings
from .floor import CLEARANCE_M, FRONT_M, HALF_WIDTH_M, REAR_M, blocker, free_ahead
from .loader import display_path
from .simulation import SimulationSettings, load_simulation_settings, simulation_yaml
from .trip import TIME_MAX_S, VELOCITY_MAX_MPS, answer_trip

__all__ = [
    "LESSON7_DRIVE_S",
    "check_files_together",
    "check_together",
    "free_distance_m",
    "key_line",
    "load_checked_settings",
]

LESSON7_DRIVE_S = 3.0  # lesson 7 drives for 3 s of simulated time at default_velocity_mps
_STOP_M = 0.05  # how far the robot rolls after its velocity drops to 0

Where = Callable[[str, str], tuple[str, int | None]]


def _blocker(sim: SimulationSettings, distance: float) -> str | None:
    """Return what the robot meets driving `distance` straight ahead from its start, or None."""
    pose = sim.start_pose
    return blocker(sim, pose.x_m, pose.y_m, math.radians(pose.yaw_deg), distance)


def free_distance_m(sim: SimulationSettings, limit: float = 3.0) -> float:
    """Return how far the robot can drive straight ahead from its start pose (cm steps)."""
    pose = sim.start_pose
    return free_ahead(sim, pose.x_m, pose.y_m, math.radians(pose.yaw_deg), limit=limit).free_m


def _start_problems(sim: SimulationSettings, where: Where) -> list[ConfigError]:
    blocker = _blocker(sim, 0.0)
    if blocker is None:
        return []
    pose = sim.start_pose
    return [
        ConfigError(
            *where("simulation.yaml", "start_pose"),
            "start_pose",
            f"the robot at ({pose.x_m:g}, {pose.y_m:g}) facing {pose.yaw_deg:g}° overlaps "
            f"{blocker} (it needs {REAR_M + CLEARANCE_M:.2f} m behind, "
            f"{FRONT_M + CLEARANCE_M:.2f} m ahead and {HALF_WIDTH_M + CLEARANCE_M:.2f} m "
            "to each side)",
            f"move start_pose or {blocker} so that the robot stands clear of it.",
        )
    ]


def _drive_problem(
    sim: SimulationSettings, key: str, needed: float, what: str, where: Where
) -> ConfigError | None:
    blocker = _blocker(sim, needed)
    if blocker is None:
        return None
    pose = sim.start_pose
    free = free_distance_m(sim, needed)
    start_file, start_line = where("simulation.yaml", "start_pose")
    return ConfigError(
        *where("course.yaml", key),
        key,
        f"{what} needs {needed:.2f} m of free floor straight ahead of the start pose "
        f"({pose.x_m:g}, {pose.y_m:g}) facing {pose.yaw_deg:g}° "
        f"({start_file}, line {start_line}), but {blocker} is {free:.2f} m ahead",
        f"turn or move start_pose in simulation.yaml towards free floor, move {blocker}, or "
        f"lower {key.rsplit('.', 1)[-1]} so the drive needs at most {free:.2f} m.",
    )


def _exercise_problems(course: CourseSettings, where: Where) -> list[ConfigError]:
    task = course.travel_exercise
    trip = answer_trip(task.target_m, task.tolerance_m, course.default_velocity_mps)
    if trip is None:
        return [
            ConfigError(
                *where("course.yaml", "travel_exercise.target_m"),
                "travel_exercise.target_m",
                f"no velocity (0.01 to {VELOCITY_MAX_MPS} m/s in steps of 0.01) and travel_time "
                f"(0.1 to {TIME_MAX_S:g} s in steps of 0.1) of descriptor_vel_node lands within "
                f"half the tolerance of {task.target_m:g} m",
                "use a target with at most two decimals, or a larger tolerance_m.",
            )
        ]
    if task.timeout_s < trip.travel_time_s + 5.0:
        return [
            ConfigError(
                *where("course.yaml", "travel_exercise.timeout_s"),
                "travel_exercise.timeout_s",
                f"{task.timeout_s:g} s is too short: the answer's trip alone takes "
                f"{trip.travel_time_s:g} s",
                f"use at least {trip.travel_time_s + 5.0:g} s.",
            )
        ]
    return []


def check_together(
    course: CourseSettings, sim: SimulationSettings, where: Where
) -> list[ConfigError]:
    """Return every problem of course.yaml and simulation.yaml taken together.

    `where(file name, dotted key)` gives the file's path as shown and the key's line in it.
    """
    problems = _start_problems(sim, where) + _exercise_problems(course, where)
    if problems:
        return problems
    task = course.travel_exercise
    drives = [
        (
            "default_velocity_mps",
            LESSON7_DRIVE_S * course.default_velocity_mps + _STOP_M,
            f"lesson 7's drive ({LESSON7_DRIVE_S:g} s at {course.default_velocity_mps:g} m/s)",
        ),
        (
            "travel_exercise.target_m",
            task.target_m + task.tolerance_m + _STOP_M,
            f"lesson 11's exercise ({task.target_m:g} m ± {task.tolerance_m:g} m)",
        ),
        (  # the checker lets the speed settle (about 1 s) before its window
            "drive_exercise.distance_m",
            course.drive_exercise.distance_m * (1 + 1 / course.drive_exercise.time_s)
            + course.drive_exercise.tolerance_m
            + _STOP_M,
            f"lesson 7's exercise ({course.drive_exercise.distance_m:g} m in "
            f"{course.drive_exercise.time_s:g} s, after the speed settled)",
        ),
    ]
    found = [_drive_problem(sim, key, needed, what, where) for key, needed, what in drives]
    return [p for p in found if p is not None]


def key_line(path: Path, dotted: str) -> int | None:
    """Return the 1-based line of `dotted` (e.g. `start_pose.x_m`) in a YAML file, if there."""
    try:
        node = yaml.compose(path.read_text(encoding="utf-8"), Loader=yaml.SafeLoader)
    except (OSError, yaml.YAMLError):
        return None
    line = None
    for part in dotted.split("."):
        if not isinstance(node, yaml.MappingNode):
            return line
        match = next(((k, v) for k, v in node.value if k.value == part), None)
        if match is None:
            return line
        line, node = match[0].start_mark.line + 1, match[1]
    return line


def check_files_together(
    course: CourseSettings, sim: SimulationSettings, paths: dict[str, Path]
) -> list[ConfigError]:
    """Return check_together's problems, naming the files in `paths` (name -> path) and lines."""

    def where(name: str, key: str) -> tuple[str, int | None]:
        return display_path(paths[name]), key_line(paths[name], key)

    return check_together(course, sim, where)


def load_checked_settings(
    course_path: Path | None = None,
) -> tuple[CourseSettings, SimulationSettings]:
    """Load course.yaml and simulation.yaml and check them together; raise the first problem."""
    course = load_course_settings(course_path)
    sim = load_simulation_settings()
    paths = {"course.yaml": course_path or course_yaml(), "simulation.yaml": simulation_yaml()}
    problems = check_files_together(course, sim, paths)
    if problems:
        first = problems[0]
        if len(problems) > 1:
            first.hint += f" ({len(problems) - 1} more: `make check-config` lists them all.)"
        raise first
    return course, sim
