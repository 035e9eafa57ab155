"""Exercise attempts on the progress page: pass rate and median attempts to pass per exercise."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from course_lib.hub.progress.page import render_page
from course_lib.hub.progress.store import ProgressStore
from course_lib.lessons.progress.record import Record, RecordError, parse_record, record_body


def _attempt(user: str, exercise: str, number: int, passed: bool, lesson: int = 7) -> Record:
    return Record(user, lesson, passed, "", exercise, number)


def test_pass_rate_and_median_attempts_across_the_class(tmp_path: Path) -> None:
    store = ProgressStore(tmp_path / "p.db")
    for record in [
        _attempt("ada", "07 drive", 1, False),
        _attempt("ada", "07 drive", 2, True),
        _attempt("ada", "07 drive", 3, False),  # failing again later keeps the pass at 2
        _attempt("bob", "07 drive", 1, False),
        _attempt("bob", "07 drive", 2, False),
        _attempt("bob", "07 drive", 3, False),
        _attempt("bob", "07 drive", 4, True),
        _attempt("cy", "07 drive", 1, False),
        _attempt("cy", "09 params file", 1, True, lesson=9),
        _attempt("bob", "07 drive", 2, False),  # a late, out-of-order post lowers nothing
    ]:
        store.add(record)
    drive, params = store.exercise_stats()
    assert (drive.exercise, drive.tried, drive.passed, drive.median_attempts) == (
        "07 drive", 3, 2, 3.0,
    )  # fmt: skip
    assert round(drive.pass_rate, 3) == 0.667
    assert (params.lesson, params.tried, params.passed, params.median_attempts) == (9, 1, 1, 1)
    assert store.states() == []  # attempts are not self-checks
    html = render_page([], [], titles={}, exercises=store.exercise_stats())
    assert "07 drive" in html and "67 %" in html and "2 of 3" in html


def test_no_attempt_yet_says_so() -> None:
    assert "No exercise attempts yet." in render_page([], [], titles={})


def test_an_attempt_record_round_trips_and_old_records_are_unchanged() -> None:
    record = _attempt("ada", "07 drive", 2, True)
    assert parse_record(record_body(record)) == record
    old = Record("ada", 7, False, "stopped")
    assert json.loads(record_body(old)) == {
        "user": "ada", "lesson": 7, "passed": False, "failed": "stopped",
    }  # fmt: skip


@pytest.mark.parametrize(
    ("body", "words"),
    [
        ({"exercise": "07 drive", "attempt": 0}, "counts from 1"),
        ({"attempt": 2}, 'send "exercise" too'),
        ({"exercise": "x" * 41, "attempt": 1}, "longer than"),
        ({"exercise": "07 drive", "attempt": "2"}, '"attempt" must be int'),
    ],
)
def test_a_bad_attempt_record_is_refused(body: dict, words: str) -> None:
    data = {"user": "ada", "lesson": 7, "passed": False, **body}
    with pytest.raises(RecordError, match=words):
        parse_record(json.dumps(data).encode())
