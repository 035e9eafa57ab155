"""The instructor's lesson settings (config/course.yaml) as frozen dataclasses (pure)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..core.paths import config_dir
from .loader import SettingValueError, load_settings, setting

__all__ = ["CourseSettings", "TravelExercise", "course_yaml", "load_course_settings"]


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


def load_course_settings(path: str | Path | None = None) -> CourseSettings:
    """Read config/course.yaml (or `path`); a missing or empty file is a ConfigError."""
    return load_settings(Path(path) if path is not None else course_yaml(), CourseSettings)
