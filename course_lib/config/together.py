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
from .loader import display_path
from .simulation import Obstacle, SimulationSettings, load_simulation_settings, simulation_yaml
from .trip import TIME_MAX_S, VELOCITY_MAX_MPS, answer_trip

__all__ = [
    "FLOOR_HALF_M",
    "LESSON7_DRIVE_S",
    "check_files_together",
    "check_together",
    "free_distance_m",
    "key_line",
    "load_checked_settings",
]

FLOOR_HALF_M = 5.0  # scene.xml: the floor plane is 10 m × 10 m around the origin
LESSON7_DRIVE_S = 3.0  # lesson 7 drives for 3 s of simulated time at default_velocity_mps
# The Waffle Pi's footprint around base_footprint (turtlebot3_waffle_pi.xml): the base plate
# reaches 0.20 m back, the camera 0.09 m forward, the wheels 0.16 m to each side.
_REAR_M, _FRONT_M, _HALF_WIDTH_M = 0.20, 0.09, 0.16
_CLEARANCE_M = 0.05  # room kept between the robot and anything it must not touch
_STOP_M = 0.05  # how far the robot rolls after its velocity drops to 0

Point = tuple[float, float]
Where = Callable[[str, str], tuple[str, int | None]]


def _corners(
    cx: float, cy: float, yaw: float, back: float, front: float, half: float
) -> list[Point]:
    c, s = math.cos(yaw), math.sin(yaw)
    local = [(-back, -half), (front, -half), (front, half), (-back, half)]
    return [(cx + x * c - y * s, cy + x * s + y * c) for x, y in local]


def _separated(a: list[Point], b: list[Point]) -> bool:
    """Return True when convex polygons a and b do not overlap (separating axis test)."""
    for poly in (a, b):
        for i, (x1, y1) in enumerate(poly):
            x2, y2 = poly[(i + 1) % len(poly)]
            axis = (y1 - y2, x2 - x1)
            pa = [axis[0] * x + axis[1] * y for x, y in a]
            pb = [axis[0] * x + axis[1] * y for x, y in b]
            if max(pa) < min(pb) or max(pb) < min(pa):
                return True
    return False


def _hits(swept: list[Point], obstacle: Obstacle, yaw: float, origin: Point) -> bool:
    x, y = obstacle.position_m
    if obstacle.shape == "box":
        length, width = obstacle.size_m[0], obstacle.size_m[1]
        box = _corners(x, y, math.radians(obstacle.yaw_deg), length / 2, length / 2, width / 2)
        return not _separated(swept, box)
    radius = obstacle.size_m[0] / 2
    c, s = math.cos(yaw), math.sin(yaw)
    dx, dy = x - origin[0], y - origin[1]
    along, across = dx * c + dy * s, -dx * s + dy * c  # the cylinder in the robot's frame
    xs = [px * c + py * s - (origin[0] * c + origin[1] * s) for px, py in swept]
    nearest_x = min(max(along, min(xs)), max(xs))
    nearest_y = min(max(across, -_HALF_WIDTH_M - _CLEARANCE_M), _HALF_WIDTH_M + _CLEARANCE_M)
    return math.hypot(along - nearest_x, across - nearest_y) < radius


def _blocker(sim: SimulationSettings, distance: float) -> str | None:
    """Return what the robot meets driving `distance` straight ahead from its start, or None."""
    pose = sim.start_pose
    yaw = math.radians(pose.yaw_deg)
    margin = _CLEARANCE_M
    swept = _corners(
        pose.x_m,
        pose.y_m,
        yaw,
        _REAR_M + margin,
        _FRONT_M + margin + distance,
        _HALF_WIDTH_M + margin,
    )
    if any(abs(x) > FLOOR_HALF_M or abs(y) > FLOOR_HALF_M for x, y in swept):
        return "the edge of the floor"
    for obstacle in sim.obstacles:
        if _hits(swept, obstacle, yaw, (pose.x_m, pose.y_m)):
            return obstacle.name
    return None


def free_distance_m(sim: SimulationSettings, limit: float = 3.0) -> float:
    """Return how far the robot can drive straight ahead from its start pose (cm steps)."""
    step = 0.01
    distance = 0.0
    while distance + step <= limit and _blocker(sim, distance + step) is None:
        distance += step
    return round(distance, 2)


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
            f"{blocker} (it needs {_REAR_M + _CLEARANCE_M:.2f} m behind, "
            f"{_FRONT_M + _CLEARANCE_M:.2f} m ahead and {_HALF_WIDTH_M + _CLEARANCE_M:.2f} m "
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
