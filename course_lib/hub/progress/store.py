"""The progress records in SQLite: one row per (user, lesson), kept across restarts.

Each row holds the latest verdict (passed or not), when the lesson last passed, and what
failed last and when. Every write is one transaction (an upsert), so a crash leaves the row
as it was or as it is meant to be, never half-written. WAL lets the page read while a record
is written.
"""

from __future__ import annotations

import contextlib
import sqlite3
from collections.abc import Iterator
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

from ...lessons.progress.record import Record

__all__ = ["ExerciseStats", "LessonState", "ProgressStore", "StoreError"]

_SCHEMA = """
CREATE TABLE IF NOT EXISTS progress (
    user TEXT NOT NULL,
    lesson INTEGER NOT NULL,
    passed INTEGER NOT NULL,
    passed_at TEXT,
    failed TEXT NOT NULL DEFAULT '',
    failed_at TEXT,
    PRIMARY KEY (user, lesson)
)
"""
_ATTEMPTS_SCHEMA = """
CREATE TABLE IF NOT EXISTS attempts (
    user TEXT NOT NULL,
    exercise TEXT NOT NULL,
    lesson INTEGER NOT NULL,
    attempts INTEGER NOT NULL,
    passed_at_attempt INTEGER,
    PRIMARY KEY (user, exercise)
)
"""
# a learner's attempts only grow (a retried post, a second kernel's count, never lower it);
# the attempt that first passed is kept
_UPSERT_ATTEMPT = """
INSERT INTO attempts (user, exercise, lesson, attempts, passed_at_attempt) VALUES (?, ?, ?, ?, ?)
ON CONFLICT (user, exercise) DO UPDATE
SET attempts = MAX(attempts, excluded.attempts), lesson = excluded.lesson,
    passed_at_attempt = COALESCE(
        MIN(passed_at_attempt, excluded.passed_at_attempt),
        passed_at_attempt,
        excluded.passed_at_attempt
    )
"""
_UPSERT_PASSED = """
INSERT INTO progress (user, lesson, passed, passed_at) VALUES (?, ?, 1, ?)
ON CONFLICT (user, lesson) DO UPDATE SET passed = 1, passed_at = excluded.passed_at
"""
_UPSERT_FAILED = """
INSERT INTO progress (user, lesson, passed, failed, failed_at) VALUES (?, ?, 0, ?, ?)
ON CONFLICT (user, lesson) DO UPDATE
SET passed = 0, failed = excluded.failed, failed_at = excluded.failed_at
"""


class StoreError(RuntimeError):
    """The database cannot be opened or written: the message names the file."""


@dataclass(frozen=True)
class LessonState:
    """One learner's state in one lesson (times are UTC datetimes)."""

    user: str
    lesson: int
    passed: bool
    passed_at: datetime | None
    failed: str
    failed_at: datetime | None

    def as_json(self) -> dict[str, object]:
        """Return the state as JSON-ready data (times in ISO 8601, UTC)."""
        return {
            "user": self.user,
            "lesson": self.lesson,
            "passed": self.passed,
            "passed_at": self.passed_at.isoformat() if self.passed_at else None,
            "failed": self.failed,
            "failed_at": self.failed_at.isoformat() if self.failed_at else None,
        }


@dataclass(frozen=True)
class ExerciseStats:
    """One exercise across the class: who tried, who passed, the median attempts to pass."""

    exercise: str
    lesson: int
    tried: int
    passed: int
    median_attempts: float | None  # among those who passed; None when nobody has yet

    @property
    def pass_rate(self) -> float:
        return self.passed / self.tried if self.tried else 0.0

    def as_json(self) -> dict[str, object]:
        return {
            "exercise": self.exercise,
            "lesson": self.lesson,
            "tried": self.tried,
            "passed": self.passed,
            "pass_rate": self.pass_rate,
            "median_attempts": self.median_attempts,
        }


def _time(text: str | None) -> datetime | None:
    return datetime.fromisoformat(text) if text else None


class ProgressStore:
    """The SQLite file of the progress records (created, with its folder, on first use)."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._db = sqlite3.connect(self.path, isolation_level=None)
            self._db.execute("PRAGMA journal_mode=WAL")
            self._db.execute(_SCHEMA)
            self._db.execute(_ATTEMPTS_SCHEMA)
        except (OSError, sqlite3.Error) as error:
            raise StoreError(
                f"cannot open the progress database {self.path}: {error}. "
                "Give a writable file with --db (or COURSE_PROGRESS_DB)."
            ) from None

    def close(self) -> None:
        """Close the database."""
        self._db.close()

    def add(self, record: Record, when: datetime | None = None) -> None:
        """Store a self-check's verdict (one transaction)."""
        stamp = (when or datetime.now(UTC)).astimezone(UTC).isoformat(timespec="seconds")
        key = (record.user, record.lesson)
        try:
            with self._transaction():
                if record.exercise:
                    passed_at = record.attempt if record.passed else None
                    row = (record.user, record.exercise, record.lesson, record.attempt, passed_at)
                    self._db.execute(_UPSERT_ATTEMPT, row)
                elif record.passed:
                    self._db.execute(_UPSERT_PASSED, (*key, stamp))
                else:
                    self._db.execute(_UPSERT_FAILED, (*key, record.failed, stamp))
        except sqlite3.Error as error:
            raise StoreError(f"cannot write to {self.path}: {error}") from None

    @contextlib.contextmanager
    def _transaction(self) -> Iterator[None]:
        """BEGIN IMMEDIATE ... COMMIT, or ROLLBACK on error.

        The connection is in autocommit mode (isolation_level=None), where `with connection:`
        begins nothing: the transaction is opened here, taking the write lock at once.
        """
        self._db.execute("BEGIN IMMEDIATE")
        try:
            yield
        except BaseException:
            self._db.execute("ROLLBACK")
            raise
        self._db.execute("COMMIT")

    def states(self) -> list[LessonState]:
        """Return every stored state, by user then lesson."""
        rows = self._db.execute(
            "SELECT user, lesson, passed, passed_at, failed, failed_at FROM progress "
            "ORDER BY user, lesson"
        ).fetchall()
        return [
            LessonState(user, lesson, bool(passed), _time(p_at), failed, _time(f_at))
            for user, lesson, passed, p_at, failed, f_at in rows
        ]

    def exercise_stats(self) -> list[ExerciseStats]:
        """Return each exercise's pass rate and median attempts to pass, by lesson."""
        import statistics

        rows = self._db.execute(
            "SELECT exercise, lesson, attempts, passed_at_attempt FROM attempts "
            "ORDER BY lesson, exercise"
        ).fetchall()
        by_exercise: dict[str, list[tuple[int, int, int | None]]] = {}
        for exercise, lesson, attempts, passed_at in rows:
            by_exercise.setdefault(exercise, []).append((lesson, attempts, passed_at))
        stats = []
        for exercise, entries in by_exercise.items():
            passes = [p for _l, _a, p in entries if p is not None]
            median = statistics.median(passes) if passes else None
            stats.append(
                ExerciseStats(exercise, entries[-1][0], len(entries), len(passes), median)
            )
        return sorted(stats, key=lambda s: (s.lesson, s.exercise))
