"""The instructor's lesson settings (config/course.yaml) as frozen dataclasses (pure)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..config.loader import SettingValueError, load_settings, setting
from ..paths import CONFIG_DIR

__all__ = ["COURSE_YAML", "CourseSettings", "TravelExercise", "load_course_settings"]

COURSE_YAML = CONFIG_DIR / "course.yaml"


@dataclass(frozen=True)
class TravelExercise:
    """Lesson 11's exercise: travel `target_m` (within `tolerance_m`) and stop."""

    target_m: float = setting(1.0, help="distance to travel", gt=0.0, le=1.5)
    tolerance_m: float = setting(0.05, help="allowed error", gt=0.0, le=0.5)
    timeout_s: float = setting(30.0, help="simulated seconds to wait for a stop", gt=0.0)

    def __post_init__(self) -> None:
        if self.tolerance_m >= self.target_m:
            raise SettingValueError(
                "tolerance_m",
                f"{self.tolerance_m} is not smaller than target_m ({self.target_m})",
                "use a tolerance well below the target, e.g. 0.05.",
            )


@dataclass(frozen=True)
class CourseSettings:
    """What an instructor may change about the lessons."""

    default_velocity_mps: float = setting(0.2, help="speed the lessons drive at", gt=0.0, le=0.26)
    show_hints: bool = setting(True, help="hints after a failed exercise attempt")
    travel_exercise: TravelExercise = TravelExercise()


def load_course_settings(path: str | Path | None = None) -> CourseSettings:
    """Read config/course.yaml (or `path`); the defaults when the file does not exist."""
    path = Path(path) if path is not None else COURSE_YAML
    if path == COURSE_YAML and not path.exists():
        return CourseSettings()
    return load_settings(path, CourseSettings)
