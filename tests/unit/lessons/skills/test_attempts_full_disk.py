"""An exercise's attempt count that cannot be saved (a full disk): the verdict still shows,
with one line saying so, and the count goes on and is saved once there is room."""

from __future__ import annotations

import errno
import json
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest

from course_lib.core.files.atomic_files import FileSaveError
from course_lib.lessons.skills import attempts
from course_lib.lessons.skills.attempts import ATTEMPTS_FILE, AttemptLog
from course_lib.lessons.skills.exercise_base import SkillExercise
from course_lib.lessons.skills.judge import Verdict

UNSAVED = (
    "Your attempt count was not saved in my_files/.exercise_attempts.json (the disk is full): "
    "this notebook keeps counting and saves it with your next check."
)


def _full_disk(path: Any, text: str) -> Path:
    raise FileSaveError(path, OSError(errno.ENOSPC, "No space left on device"))


class _Exercise(SkillExercise):
    """The exercise's own bookkeeping, without a robot or a node to judge."""

    name = "09 startup"

    def _others(self) -> list[str]:
        return []

    def _judge(self, number: int) -> Verdict:
        return Verdict(False, f"Attempt {number}: not yet.", "start it with the file.", "kind")

    def _stop_robot(self) -> None:
        pass

    def arm(self) -> str:
        self.armed_at = 1.0
        return ""


@pytest.fixture
def learner_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)  # the notebook's folder: my_files/ is under it
    return tmp_path / "my_files"


def test_a_count_not_saved_is_said_kept_and_saved_with_the_next(
    learner_dir: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    log = AttemptLog(learner_dir)
    log.add("09 startup", passed=False)
    with monkeypatch.context() as full:
        full.setattr(attempts, "atomic_write", _full_disk)
        second = log.add("09 startup", passed=False)
        third = log.add("09 startup", passed=True)
    assert (second.attempts, second.unsaved) == (2, UNSAVED)
    assert (third.attempts, third.passed, third.unsaved) == (3, True, UNSAVED)
    saved = json.loads((learner_dir / ATTEMPTS_FILE).read_text())
    assert saved == {"09 startup": {"attempts": 1, "passed": False}}  # the old file, whole
    fourth = log.add("09 startup", passed=False)
    assert (fourth.attempts, fourth.passed, fourth.unsaved) == (4, True, "")
    assert AttemptLog(learner_dir).tally("09 startup").attempts == 4  # in the file now


def test_the_verdict_still_shows_with_one_line_that_the_count_was_not_saved(
    learner_dir: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    lesson = SimpleNamespace(learner_dir=learner_dir, state={}, number=9)
    exercise = _Exercise(lesson)
    exercise.arm()
    with monkeypatch.context() as full:
        full.setattr(attempts, "atomic_write", _full_disk)
        verdict = exercise.check()
    assert repr(verdict) == f"Attempt 1: not yet.\nHint: start it with the file.\n{UNSAVED}\n"
    again = exercise.check()
    assert repr(again) == "Attempt 2: not yet.\nHint: start it with the file.\n"
    assert AttemptLog(learner_dir).tally("09 startup").attempts == 2
