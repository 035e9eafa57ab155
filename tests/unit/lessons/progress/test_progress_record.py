"""What a self-check posts: the JSON the client builds is the JSON the service accepts."""

from __future__ import annotations

import json

import pytest

from course_lib.lessons.progress.record import (
    MAX_FAILED_CHARS,
    Record,
    RecordError,
    parse_record,
    record_body,
)


def test_the_clients_body_parses_back() -> None:
    record = Record("alice", 7, False, "The robot drives at 0.2 m/s")
    assert parse_record(record_body(record)) == record


def test_a_long_failed_text_is_cut_by_the_client() -> None:
    body = record_body(Record("alice", 7, False, "x" * (MAX_FAILED_CHARS + 50)))
    assert len(parse_record(body).failed) == MAX_FAILED_CHARS


@pytest.mark.parametrize(
    ("data", "says"),
    [
        ([1, 2], "JSON object"),
        ({"user": "", "lesson": 1, "passed": True}, "empty"),
        ({"user": "a", "lesson": 12, "passed": True}, "1 to 11"),
        ({"user": "a", "lesson": True, "passed": True}, '"lesson" must be int'),
        ({"user": "a", "lesson": "7", "passed": True}, '"lesson" must be int'),
        ({"user": "a", "lesson": 7, "passed": 1}, '"passed" must be bool'),
        ({"user": "a", "lesson": 7}, '"passed" must be bool'),
        ({"user": 3, "lesson": 7, "passed": True}, '"user" must be str'),
        ({"user": "a", "lesson": 7, "passed": True, "failed": "x"}, "no failed check"),
        ({"user": "a", "lesson": 7, "passed": False, "who": "b"}, "unknown field(s) who"),
        ({"user": "a", "lesson": 7, "passed": False, "failed": "x" * 501}, "longer than"),
    ],
)
def test_a_bad_record_says_what_is_wrong(data: object, says: str) -> None:
    with pytest.raises(RecordError, match=None) as raised:
        parse_record(json.dumps(data).encode())
    assert says in str(raised.value)


def test_a_body_that_is_not_json() -> None:
    with pytest.raises(RecordError, match="not JSON"):
        parse_record(b"\xff{")


def test_a_record_names_one_of_the_lessons_exercises_or_is_refused() -> None:
    import json

    from course_lib.lessons.progress.record import EXERCISES

    def body(exercise: str, lesson: int) -> bytes:
        fields = {"user": "ada", "lesson": lesson, "passed": False, "failed": ""}
        return json.dumps({**fields, "exercise": exercise, "attempt": 1}).encode()

    assert parse_record(body("07 drive", 7)).exercise == "07 drive"
    made_up = [body(f"exercise {n}", 7) for n in range(2000)]  # once a 4.3 MB store
    for posted in [*made_up, body("07 drive", 9)]:
        with pytest.raises(RecordError, match="no exercise of lesson"):
            parse_record(posted)
    assert len(EXERCISES) == 5


def test_the_list_of_exercises_is_the_lessons_own() -> None:
    from course_lib.lessons.exercise import NAME as TRAVEL
    from course_lib.lessons.progress.record import EXERCISES
    from course_lib.lessons.skills import exercises

    skills = [
        exercises.DriveExercise,
        exercises.ParamsFileExercise,
        exercises.LaunchExercise,
        exercises.SavedPanelExercise,
    ]
    names = {kind.name for kind in skills} | {TRAVEL}
    assert names == set(EXERCISES)
    assert all(EXERCISES[name] == int(name.split()[0]) for name in names)
