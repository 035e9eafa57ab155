"""The class's progress store killed in the middle of a burst of records (issue 62, item 2):
every record it acknowledged is kept, and the store opens cleanly afterwards.

A writer process stores exercise attempts as fast as it can, one transaction each, and says
"stored N" after each `add` returns (what the service does before it answers 201). It is
SIGKILLed at a random moment, 25 times over, each time on the same database; after each kill
the database passes SQLite's integrity check and every (learner, exercise) holds at least
the last attempt acknowledged for it.
"""

from __future__ import annotations

import os
import random
import select
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from course_lib.hub.progress.store import ProgressStore

pytestmark = pytest.mark.slow

KILLS = 25
LEARNERS = ("alice", "bob", "carol", "dave")
EXERCISES = ("l07_drive", "l09_start_fast", "l10_launch", "l11_travel")

_WRITER_LOOP = """
import sys
from course_lib.hub.progress.store import ProgressStore
from course_lib.lessons.progress.record import Record
learners, exercises = sys.argv[2].split(","), sys.argv[3].split(",")
store = ProgressStore(sys.argv[1])
attempt = int(sys.argv[4])
while True:
    attempt += 1
    for learner in learners:
        for number, exercise in enumerate(exercises):
"""
_STORE = "            store.add(Record(learner, 7 + number, False, '', exercise, attempt))\n"
_ACK = "            print(f'stored {learner} {exercise} {attempt}', flush=True)\n"
_WRITER = _WRITER_LOOP + _STORE + _ACK  # what the service does: store, then answer


def _lines_until_killed(writer: subprocess.Popen[str], after_s: float) -> list[str]:
    """Let the writer write for `after_s` seconds, SIGKILL it, and return the whole lines it
    said (the last may have been cut by the kill)."""
    assert writer.stdout is not None
    fd = writer.stdout.fileno()
    os.set_blocking(fd, False)
    said = b""
    deadline = time.monotonic() + after_s
    while (left := deadline - time.monotonic()) > 0:
        if select.select([fd], [], [], left)[0]:
            said += os.read(fd, 65536)
    writer.send_signal(signal.SIGKILL)
    writer.wait()
    os.set_blocking(fd, True)
    said += writer.stdout.buffer.read()
    return said.decode().split("\n")[:-1]


def _acknowledged(lines: list[str]) -> dict[tuple[str, str], int]:
    latest: dict[tuple[str, str], int] = {}
    for line in lines:
        if line.startswith("stored "):
            _, learner, exercise, attempt = line.split()
            latest[(learner, exercise)] = int(attempt)
    return latest


def _stored(path: Path) -> dict[tuple[str, str], int]:
    """Return the attempts the database holds (none if the writer was killed before its
    store had made the table: a busy host starts Python in up to a second)."""
    with sqlite3.connect(path) as db:
        assert db.execute("PRAGMA integrity_check").fetchone() == ("ok",)
        table = "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'attempts'"
        if db.execute(table).fetchone() is None:
            return {}
        rows = db.execute("SELECT user, exercise, attempts FROM attempts").fetchall()
    return {(user, exercise): attempts for user, exercise, attempts in rows}


def _kill_repeatedly(path: Path, writer_code: str, kills: int) -> tuple[list[str], int]:
    """Kill a writer `kills` times at random moments; return what each kill lost (acked
    attempts not stored) and how many acknowledgements there were in all."""
    chance = random.Random(62)
    attempt, acknowledged_in_all, losses = 0, 0, []
    for kill in range(kills):
        with subprocess.Popen(
            [sys.executable, "-c", writer_code, str(path), ",".join(LEARNERS),
             ",".join(EXERCISES), str(attempt)],
            stdout=subprocess.PIPE, text=True,
        ) as writer:  # fmt: skip
            lines = _lines_until_killed(writer, chance.uniform(0.3, 1.2))
        acknowledged = _acknowledged(lines)
        acknowledged_in_all += len([line for line in lines if line.startswith("stored ")])
        stored = _stored(path)
        lost = {k: (n, stored.get(k)) for k, n in acknowledged.items() if stored.get(k, 0) < n}
        if lost:
            losses.append(f"kill {kill}: acknowledged attempts lost (acked, stored): {lost}")
        attempt = max(stored.values(), default=attempt)
        ProgressStore(path).close()  # opens cleanly after the kill
    return losses, acknowledged_in_all


def test_every_acknowledged_record_survives_a_kill_at_a_random_moment(tmp_path: Path) -> None:
    losses, acknowledged = _kill_repeatedly(tmp_path / "progress.sqlite", _WRITER, KILLS)
    assert losses == []
    assert acknowledged > KILLS * 10, "the writer hardly wrote: the kills tested nothing"


def test_a_writer_killed_before_its_store_made_the_table_stored_nothing(tmp_path: Path) -> None:
    """The first kill can land while the writer's Python still starts (a CI rerun: "no such
    table: attempts"): nothing was stored, and nothing acknowledged."""
    assert _stored(tmp_path / "progress.sqlite") == {}


def test_the_check_catches_a_writer_that_acknowledges_before_it_stores(tmp_path: Path) -> None:
    """The probe: the same kills on a writer that says "stored" before `add` returns."""
    early = _WRITER_LOOP + _ACK + _STORE
    losses, _ = _kill_repeatedly(tmp_path / "progress.sqlite", early, 8)
    assert losses, "a writer that acknowledges first lost nothing in 8 kills: the check is blind"
