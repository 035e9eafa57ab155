"""The parameter journal: private, append-only, whole lines from several processes at once."""

from __future__ import annotations

import multiprocessing
import os
import stat

import pytest

from course_lib.core import param_journal

DOMAIN = 231  # beyond the course's leases: no lab writes here


@pytest.fixture(autouse=True)
def _clean() -> None:
    param_journal.journal_path(DOMAIN).unlink(missing_ok=True)
    yield
    param_journal.journal_path(DOMAIN).unlink(missing_ok=True)


def _writer(count: int) -> None:
    for n in range(count):
        param_journal.append(DOMAIN, {"t": "set", "n": n, "pad": "x" * 3000})


def test_lines_of_several_processes_never_interleave() -> None:
    context = multiprocessing.get_context("spawn")
    writers = [context.Process(target=_writer, args=(50,)) for _ in range(4)]
    for w in writers:
        w.start()
    for w in writers:
        w.join(60)
    records = param_journal.read_journal(DOMAIN)
    assert len(records) == 200
    assert {r["pid"] for r in records} == {w.pid for w in writers}
    mode = stat.S_IMODE(os.stat(param_journal.journal_path(DOMAIN)).st_mode)
    assert mode == 0o600, "the learner's alone"


def test_a_torn_line_is_skipped_and_the_door_is_scoped() -> None:
    param_journal.append(DOMAIN, {"t": "a", "door": param_journal.current_door()})
    with param_journal.journal_path(DOMAIN).open("a") as handle:
        handle.write('{"t": "half')
    with param_journal.acting_door("panel"):
        param_journal.append(DOMAIN, {"t": "b", "door": param_journal.current_door()})
    doors = [(r["t"], r["door"]) for r in param_journal.read_journal(DOMAIN)]
    assert doors == [("a", "Python"), ("b", "panel")]  # the torn line alone is lost


def test_an_overlong_journal_keeps_its_newer_half(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(param_journal, "JOURNAL_MAX_BYTES", 20_000)
    for n in range(100):
        param_journal.append(DOMAIN, {"t": "set", "n": n, "pad": "x" * 400})
    records = param_journal.read_journal(DOMAIN)
    assert param_journal.journal_path(DOMAIN).stat().st_size <= 20_000 + 500
    assert records[-1]["n"] == 99 and 10 < len(records) < 60
    assert [r["n"] for r in records] == list(range(records[0]["n"], 100))


def test_a_tail_reads_only_what_was_appended_since() -> None:
    tail = param_journal.JournalTail(DOMAIN)
    assert tail.read() == ([], False)  # no journal yet
    param_journal.append(DOMAIN, {"t": "a"})
    param_journal.append(DOMAIN, {"t": "b"})
    records, restarted = tail.read()
    assert [r["t"] for r in records] == ["a", "b"] and not restarted
    assert tail.read() == ([], False)
    with param_journal.journal_path(DOMAIN).open("a") as handle:
        handle.write('{"t": "hal')  # a line being written: read once it is whole
    assert tail.read() == ([], False)
    with param_journal.journal_path(DOMAIN).open("a") as handle:
        handle.write('f"}\n')
    param_journal.append(DOMAIN, {"t": "c"})
    assert [r["t"] for r in tail.read()[0]] == ["half", "c"]


def test_a_tail_starts_over_when_the_journal_was_cut_or_replaced(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    tail = param_journal.JournalTail(DOMAIN)
    param_journal.append(DOMAIN, {"t": "old", "pad": "x" * 400})
    assert len(tail.read()[0]) == 1
    monkeypatch.setattr(param_journal, "JOURNAL_MAX_BYTES", 4_000)
    for n in range(20):  # cut to its newer half on the way, which then grows past the tail
        param_journal.append(DOMAIN, {"t": "set", "n": n, "pad": "y" * 400})
    records, restarted = tail.read()
    assert restarted and [r["n"] for r in records] == [
        r["n"] for r in param_journal.read_journal(DOMAIN)
    ]
    param_journal.journal_path(DOMAIN).unlink()
    assert tail.read() == ([], True)  # gone: what it said is forgotten
    param_journal.append(DOMAIN, {"t": "new"})
    assert tail.read() == ([{**param_journal.read_journal(DOMAIN)[0]}], False)


def test_a_tail_may_start_near_the_end() -> None:
    for n in range(10):
        param_journal.append(DOMAIN, {"t": "set", "n": n, "pad": "x" * 100})
    size = param_journal.journal_path(DOMAIN).stat().st_size
    tail = param_journal.JournalTail(DOMAIN, start_bytes=size // 2)
    records, _restarted = tail.read()
    assert [r["n"] for r in records] == list(range(10 - len(records), 10))  # whole lines
    assert 3 <= len(records) <= 5
    param_journal.append(DOMAIN, {"t": "set", "n": 10})
    assert [r["n"] for r in tail.read()[0]] == [10]
