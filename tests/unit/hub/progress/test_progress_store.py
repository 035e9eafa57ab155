"""The progress records in SQLite: one row per (user, lesson), latest verdict, kept on disk."""

from __future__ import annotations

import sqlite3
from datetime import UTC, datetime, timedelta
from pathlib import Path

import pytest

from course_lib.hub.progress.store import ProgressStore, StoreError
from course_lib.lessons.progress.record import Record

T0 = datetime(2026, 11, 23, 19, 0, tzinfo=UTC)


def test_a_pass_then_a_fail_keeps_when_it_last_passed(tmp_path: Path) -> None:
    store = ProgressStore(tmp_path / "progress.sqlite")
    store.add(Record("alice", 7, True), when=T0)
    store.add(Record("alice", 7, False, "The robot drives"), when=T0 + timedelta(minutes=5))
    (state,) = store.states()
    assert (state.user, state.lesson, state.passed) == ("alice", 7, False)
    assert state.passed_at == T0 and state.failed == "The robot drives"
    assert state.failed_at == T0 + timedelta(minutes=5)


def test_a_fail_then_a_pass_is_passed_and_remembers_the_failure(tmp_path: Path) -> None:
    store = ProgressStore(tmp_path / "progress.sqlite")
    store.add(Record("bob", 3, False, "The world runs"), when=T0)
    store.add(Record("bob", 3, True), when=T0 + timedelta(minutes=1))
    (state,) = store.states()
    assert state.passed and state.passed_at == T0 + timedelta(minutes=1)
    assert state.failed == "The world runs" and state.failed_at == T0


def test_one_row_per_user_and_lesson_sorted(tmp_path: Path) -> None:
    store = ProgressStore(tmp_path / "progress.sqlite")
    for user, lesson in [("bob", 2), ("alice", 7), ("alice", 1), ("alice", 7)]:
        store.add(Record(user, lesson, True), when=T0)
    assert [(s.user, s.lesson) for s in store.states()] == [("alice", 1), ("alice", 7), ("bob", 2)]


def test_records_survive_reopening_the_file(tmp_path: Path) -> None:
    path = tmp_path / "state" / "progress.sqlite"  # the folder is created
    first = ProgressStore(path)
    first.add(Record("alice", 11, True), when=T0)
    first.close()
    again = ProgressStore(path)
    assert [s.as_json() for s in again.states()] == [
        {"user": "alice", "lesson": 11, "passed": True, "passed_at": T0.isoformat(),
         "failed": "", "failed_at": None}
    ]  # fmt: skip
    with sqlite3.connect(path) as db:  # WAL: readers do not wait for the writer
        assert db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"


def test_an_unwritable_place_says_which_file(tmp_path: Path) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    with pytest.raises(StoreError, match=r"a-file/progress.sqlite.*--db"):
        ProgressStore(blocker / "progress.sqlite")


class _SpyConnection:
    """The store's connection, noting whether each write runs inside a transaction."""

    def __init__(self, db: sqlite3.Connection) -> None:
        self.db = db
        self.in_transaction_at_write: list[bool] = []

    def execute(self, sql: str, *args: object) -> sqlite3.Cursor:
        if sql.lstrip().startswith("INSERT"):
            self.in_transaction_at_write.append(self.db.in_transaction)
        return self.db.execute(sql, *args)

    def __enter__(self) -> _SpyConnection:
        self.db.__enter__()
        return self

    def __exit__(self, *exc: object) -> bool | None:
        return self.db.__exit__(*exc)  # type: ignore[arg-type]

    def __getattr__(self, name: str) -> object:
        return getattr(self.db, name)


def test_each_write_runs_in_a_transaction_it_promises(tmp_path: Path) -> None:
    store = ProgressStore(tmp_path / "progress.sqlite")
    spy = _SpyConnection(store._db)
    store._db = spy  # type: ignore[assignment]
    store.add(Record("alice", 7, True), when=T0)
    store.add(Record("alice", 7, False, "The robot drives"), when=T0)
    assert spy.in_transaction_at_write == [True, True]
    assert not spy.db.in_transaction  # committed


def test_a_failed_write_is_rolled_back(tmp_path: Path) -> None:
    store = ProgressStore(tmp_path / "progress.sqlite")
    with pytest.raises(RuntimeError), store._transaction():
        store._db.execute("INSERT INTO progress (user, lesson, passed) VALUES ('eve', 1, 1)")
        raise RuntimeError("after the write")
    assert store.states() == [] and not store._db.in_transaction
