"""The four skill exercises a lesson arms: `ex = lesson.<name>_exercise()`, then `ex.check()`.

Lesson 7's drive (`drive_exercise`) and the start-up exercises of lessons 9, 10 and 11
(`startup_exercises`), all built on `exercise_base.SkillExercise`.
"""

from __future__ import annotations

from .drive_exercise import DriveExercise
from .exercise_base import SkillExercise
from .startup_exercises import LaunchExercise, ParamsFileExercise, SavedPanelExercise

__all__ = [
    "DriveExercise",
    "LaunchExercise",
    "ParamsFileExercise",
    "SavedPanelExercise",
    "SkillExercise",
]
