"""The instructor's lesson settings (config/course.yaml) as frozen dataclasses (pure)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..core.paths import config_dir
from .loader import SettingValueError, load_settings, setting

__all__ = [
    "CourseSettings",
    "DriveExercise",
    "StartupExercises",
    "TravelExercise",
    "course_yaml",
    "load_course_settings",
]


def course_yaml() -> Path:
    """Return the path of course.yaml in the instructor's config folder."""
    return config_dir() / "course.yaml"


@dataclass(frozen=True)
class TravelExercise:
    """Lesson 11's exercise: drive this far with parameters only, and stop."""

    target_m: float = setting(
        1.0, help="the distance to travel (m); at most the node's max_travel", ge=0.2, le=1.5
    )
    tolerance_m: float = setting(
        0.05,
        help="how far from the target still passes (m), at most a quarter of target_m; "
        "the robot stops to about 1 cm",
        ge=0.02,
        le=0.3,
    )
    timeout_s: float = setting(
        30.0, help="simulated seconds the checker waits for the robot to stop", ge=5.0, le=120.0
    )

    def __post_init__(self) -> None:
        if self.tolerance_m > self.target_m / 4:
            raise SettingValueError(
                "tolerance_m",
                f"{self.tolerance_m} is more than a quarter of target_m ({self.target_m}): "
                "a deliberately wrong attempt would pass",
                f"use a tolerance of at most {self.target_m / 4:.2f} m.",
            )


@dataclass(frozen=True)
class DriveExercise:
    """Lesson 7's exercise: set velocity on the running node to drive this far in this time."""

    distance_m: float = setting(
        0.45,
        help="the distance to drive (m) in time_s; distance_m / time_s is the answer's velocity, "
        "at most 0.26 m/s",
        ge=0.1,
        le=1.0,
    )
    time_s: float = setting(
        3.0, help="the simulated seconds the checker measures the drive for", ge=1.0, le=10.0
    )
    tolerance_m: float = setting(
        0.03,
        help="how far from distance_m still passes (m), at most a quarter of distance_m",
        ge=0.01,
        le=0.2,
    )

    def __post_init__(self) -> None:
        if self.distance_m / self.time_s > 0.26 + 1e-9:
            raise SettingValueError(
                "distance_m",
                f"{self.distance_m} m in {self.time_s} s needs "
                f"{self.distance_m / self.time_s:.3f} m/s, faster than the robot (0.26 m/s)",
                f"use a distance of at most {0.26 * self.time_s:.2f} m, or a longer time_s.",
            )
        if self.tolerance_m > self.distance_m / 4:
            raise SettingValueError(
                "tolerance_m",
                f"{self.tolerance_m} is more than a quarter of distance_m ({self.distance_m}): "
                "a deliberately wrong attempt would pass",
                f"use a tolerance of at most {self.distance_m / 4:.2f} m.",
            )


@dataclass(frozen=True)
class StartupExercises:
    """Lessons 9, 10 and 11's exercises: the node starts with a value from a file."""

    params_file_mps: float = setting(
        0.12,
        help="lesson 9: the velocity (m/s) the learner's edited dump starts param_vel_node at",
        ge=0.05,
        le=0.26,
    )
    launch_mps: float = setting(
        0.18,
        help="lesson 10: the velocity (m/s) the learner's launch file starts param_vel_node at",
        ge=0.05,
        le=0.26,
    )
    saved_panel_travel_s: float = setting(
        2.0,
        help="lesson 11: the travel_time (s) set with the panel, saved, and passed to the "
        "restarted descriptor_vel_node; a multiple of 0.1",
        ge=0.5,
        le=5.0,
    )
    travel_tolerance_s: float = setting(
        0.15,
        help="how far from saved_panel_travel_s the measured trip may be (s)",
        ge=0.05,
        le=0.5,
    )
    tolerance_mps: float = setting(
        0.01,
        help="how far from the target the measured speed may be (m/s); the robot holds its "
        "speed to about 0.002",
        ge=0.005,
        le=0.03,
    )
    window_s: float = setting(
        2.0,
        help="the speed is measured this many simulated seconds after the robot began to "
        "move (after the node's first log line if it stood still): its first seconds",
        ge=1.0,
        le=5.0,
    )

    def __post_init__(self) -> None:
        tenths = self.saved_panel_travel_s * 10
        if abs(tenths - round(tenths)) > 1e-6:
            raise SettingValueError(
                "saved_panel_travel_s",
                f"{self.saved_panel_travel_s} is not a multiple of 0.1: the panel's slider and "
                "descriptor_vel_node's range step cannot reach it",
                f"use {round(self.saved_panel_travel_s, 1):g}.",
            )
        # lesson 10 runs the tutorial's launch files at these speeds: they must not pass
        for shown in (0.2, 0.15):
            if abs(self.launch_mps - shown) <= self.tolerance_mps:
                raise SettingValueError(
                    "launch_mps",
                    f"{self.launch_mps} is within tolerance_mps of {shown}, the velocity a "
                    "launch file lesson 10 runs already gives: the exercise would pass unsolved",
                    f"use a velocity at least {self.tolerance_mps * 2:g} m/s from 0.2 and 0.15.",
                )


@dataclass(frozen=True)
class CourseSettings:
    """What an instructor may change about the lessons."""

    default_velocity_mps: float = setting(
        0.2,
        help="the speed the lessons drive at (m/s); lesson 7 sets it, lesson 11's answer uses "
        "it; the TurtleBot3 Waffle Pi tops out at 0.26",
        ge=0.05,
        le=0.26,
    )
    show_hints: bool = setting(
        True,
        help="show a hint after a failed exercise attempt, and under a mistaken `%ros2` command "
        "or params file in the notebooks (the terminal's `ros2` never shows hints)",
    )
    travel_exercise: TravelExercise = TravelExercise()
    drive_exercise: DriveExercise = DriveExercise()
    startup_exercises: StartupExercises = StartupExercises()


def load_course_settings(path: str | Path | None = None) -> CourseSettings:
    """Read config/course.yaml (or `path`); a missing or empty file is a ConfigError."""
    return load_settings(Path(path) if path is not None else course_yaml(), CourseSettings)
