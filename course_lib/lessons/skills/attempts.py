"""How many times the learner tried each exercise, kept in their folder across kernel restarts.

One small JSON file in notebooks/my_files/ (the learner's, not git's): exercise name ->
attempts so far and whether one passed. A restarted kernel, or a lesson run again, goes on
counting, so the hints stay as specific as the learner's attempts earned. Each attempt is also
sent to the class's progress page when the lesson runs on a hub (never waits, never raises).

A count that cannot be saved (a full disk, a read-only folder) is kept by this log and saved
with the next attempt; its tally says so in one line, for the verdict to show.
"""

from __future__ import annotations

import json
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ...core.files.atomic_files import FileSaveError, atomic_write

__all__ = ["ATTEMPTS_FILE", "AttemptLog", "Tally"]

ATTEMPTS_FILE = ".exercise_attempts.json"
_lock = threading.Lock()


@dataclass(frozen=True)
class Tally:
    """One exercise's attempts so far."""

    attempts: int = 0
    passed: bool = False
    unsaved: str = ""  # why this count is not in the file yet (one line), when it is not


class AttemptLog:
    """The attempt counts of every exercise, in `folder`/.exercise_attempts.json."""

    def __init__(self, folder: Path) -> None:
        self.path = Path(folder) / ATTEMPTS_FILE
        self._unsaved: dict[str, Any] = {}  # counts the file could not take yet

    def _read(self) -> dict[str, Any]:
        try:
            data = json.loads(self.path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            data = {}  # none yet, or a damaged file: counting starts again
        return {**data, **self._unsaved} if isinstance(data, dict) else dict(self._unsaved)

    def tally(self, exercise: str) -> Tally:
        """Return the attempts made at `exercise` so far."""
        entry = self._read().get(exercise)
        if not isinstance(entry, dict):
            return Tally()
        attempts = entry.get("attempts")
        return Tally(
            attempts if isinstance(attempts, int) and attempts > 0 else 0,
            entry.get("passed") is True,
        )

    def add(self, exercise: str, passed: bool) -> Tally:
        """Count one more attempt at `exercise`; return the new tally (its number is attempts)."""
        with _lock:
            data = self._read()
            before = self.tally(exercise)
            after = Tally(before.attempts + 1, before.passed or passed)
            data[exercise] = {"attempts": after.attempts, "passed": after.passed}
            try:
                atomic_write(self.path, json.dumps(data, indent=1, sort_keys=True) + "\n")
            except FileSaveError as error:  # a full disk: kept here, saved with the next one
                self._unsaved[exercise] = data[exercise]
                said = (
                    f"Your attempt count was not saved in {error.shown} ({error.reason}): "
                    "this notebook keeps counting and saves it with your next check."
                )
                return Tally(after.attempts, after.passed, said)
            self._unsaved.clear()  # all of them are in the file now
            return after

    def forget(self, exercise: str) -> None:
        """Start counting `exercise` from zero again (tests; an instructor's reset)."""
        with _lock:
            data = self._read()
            self._unsaved.pop(exercise, None)
            if data.pop(exercise, None) is not None:
                atomic_write(self.path, json.dumps(data, indent=1, sort_keys=True) + "\n")
