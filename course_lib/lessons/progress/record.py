"""What a self-check posts to the progress service, and how its JSON is checked (pure).

The one place the wire format is written down: the lessons' client builds the body with
`record_body`; the hub's progress service (course_lib.hub.progress), which implements the other
side of this contract, reads it with `parse_record`.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from ..catalogue import LESSONS as _CATALOGUE
from ..catalogue import NUMBERS

# The environment variable that tells a learner's server (and so its kernels) where to post:
# the service's direct URL, http://127.0.0.1:<port>/services/course-progress/. The hub sets it.
PROGRESS_URL_ENV = "COURSE_PROGRESS_URL"
# Where that URL is on the learner's own host (loopback), the account that holds its port (the
# hub's launcher: root): nothing is sent to a port another account holds. The hub sets it.
PROGRESS_HOLDER_ENV = "COURSE_PROGRESS_HOLDER_UID"
LESSONS = NUMBERS  # the lessons a record may name: the catalogue's

__all__ = [
    "EXERCISES",
    "LESSONS",
    "MAX_FAILED_CHARS",
    "PROGRESS_HOLDER_ENV",
    "PROGRESS_URL_ENV",
    "Record",
    "RecordError",
    "parse_record",
    "record_body",
]

MAX_FAILED_CHARS = 500  # the client cuts the failed check's text to this
_FIELDS = {
    "user": str,
    "lesson": int,
    "passed": bool,
    "failed": str,
    "exercise": str,
    "attempt": int,
}
MAX_EXERCISE_CHARS = 40
# The lessons' exercises, by the name their attempts are counted under, with their lesson: a
# learner's records are at most one a lesson and one an exercise (2,000 made-up names once made
# a 4.3 MB store and a 303 KB admin page). Each lesson's SPEC names its exercises;
# tests/unit/lessons/progress ties them to the exercises.
EXERCISES = {name: spec.number for spec in _CATALOGUE for name in spec.exercises}
_OPTIONAL = {"failed": "", "exercise": "", "attempt": 0}


class RecordError(ValueError):
    """A posted record the service cannot take: the message says what to fix."""


@dataclass(frozen=True)
class Record:
    """One self-check's verdict: whose, which lesson, passed or not, what failed first.

    Or, with `exercise` set, one attempt at a lesson's exercise: its number and whether it
    passed (the progress page shows each exercise's pass rate and median attempts).
    """

    user: str
    lesson: int
    passed: bool
    failed: str = ""
    exercise: str = ""
    attempt: int = 0


def record_body(record: Record) -> bytes:
    """Return the JSON body a client posts for `record` (the failed text cut to size)."""
    failed = record.failed[:MAX_FAILED_CHARS]
    fields = {"user": record.user, "lesson": record.lesson, "passed": record.passed}
    if record.exercise:
        fields.update(exercise=record.exercise, attempt=record.attempt)
    return json.dumps({**fields, "failed": failed}).encode("utf-8")


def _field(data: dict[str, Any], name: str) -> Any:
    kind = _FIELDS[name]
    value = data.get(name, _OPTIONAL.get(name))
    # bool is an int in Python: a lesson of `true` is refused, as is a passed of 1
    if not isinstance(value, kind) or (kind is int and isinstance(value, bool)):
        raise RecordError(
            f'"{name}" must be {kind.__name__} (JSON {_json_kind(kind)}), got {value!r}'
        )
    return value


def _json_kind(kind: type) -> str:
    return {str: "string", int: "integer", bool: "true or false"}[kind]


def parse_record(body: bytes) -> Record:
    """Return the record in a posted JSON body; raise RecordError saying what is wrong."""
    try:
        data = json.loads(body.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise RecordError(f"the body is not JSON: {error}") from None
    if not isinstance(data, dict):
        raise RecordError('the body must be a JSON object: {"user", "lesson", "passed", ...}')
    unknown = sorted(set(data) - set(_FIELDS))
    if unknown:
        raise RecordError(f"unknown field(s) {', '.join(unknown)}; known: {', '.join(_FIELDS)}")
    user, lesson = _field(data, "user"), _field(data, "lesson")
    passed, failed = _field(data, "passed"), _field(data, "failed")
    if not user:
        raise RecordError('"user" is empty: give the hub user name the token belongs to')
    if lesson not in LESSONS:
        raise RecordError(f'"lesson" must be {LESSONS[0]} to {LESSONS[-1]}, got {lesson}')
    if passed and failed:
        raise RecordError('a passed record has no failed check: send "failed": ""')
    if len(failed) > MAX_FAILED_CHARS:
        raise RecordError(f'"failed" is longer than {MAX_FAILED_CHARS} characters')
    exercise, attempt = _field(data, "exercise"), _field(data, "attempt")
    if len(exercise) > MAX_EXERCISE_CHARS:
        raise RecordError(f'"exercise" is longer than {MAX_EXERCISE_CHARS} characters')
    if exercise and EXERCISES.get(exercise) != lesson:
        known = ", ".join(f"{name!r} (lesson {n})" for name, n in EXERCISES.items())
        raise RecordError(f'"exercise" {exercise!r} is no exercise of lesson {lesson}: {known}')
    if exercise and attempt < 1:
        raise RecordError(f'an exercise\'s "attempt" counts from 1, got {attempt}')
    if attempt and not exercise:
        raise RecordError('"attempt" belongs to an exercise: send "exercise" too')
    return Record(user, lesson, passed, failed, exercise, attempt)
