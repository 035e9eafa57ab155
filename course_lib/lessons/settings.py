"""The instructor's lesson settings (config/course.yaml); the schema lives in course_lib.config."""

from __future__ import annotations

from ..config.course import (
    CourseSettings,
    DriveExercise,
    StartupExercises,
    TravelExercise,
    course_yaml,
    load_course_settings,
)

__all__ = [
    "CourseSettings",
    "DriveExercise",
    "StartupExercises",
    "TravelExercise",
    "course_yaml",
    "load_course_settings",
]
