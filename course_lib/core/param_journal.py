"""The lab's parameter journal: who asked for which parameter change, and what nodes reported.

One file per ROS domain (one lab, or one kernel outside a lab) in the user's private runtime
folder, readable by the learner only (0600). Every writer (a kernel, the terminal `ros2` and
its daemon, `ros2 launch`) appends one JSON line with a single `write` under an exclusive lock,
so lines of several processes never interleave and a crash leaves at most a line the reader
skips. It outlives kernels; `lesson.history()` reads it. Pure file code: no ROS.

Records (`"t"`): `set` (a course door is about to set a parameter: door, node, name, value,
old, and `writers`: the GIDs that tell that node from a restarted one), `failed` (that set was
refused), `event` (a /parameter_events message a kernel saw), `start` (the course started a
node: its `--ros-args`, from where; a terminal's `ros2 run` also the pid, as its log goes to
the terminal and the node's name is learnt from the graph),
`named` (a started process's node name, learnt from its log), `stopped` (a lesson's new driver
of the robot stopped another lesson's node: which node, who had started it, who stopped it and
for which node). A long-lived reader follows the file with a `JournalTail`.
"""

from __future__ import annotations

import contextlib
import contextvars
import fcntl
import json
import os
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from .paths import runtime_dir

__all__ = [
    "JOURNAL_MAX_BYTES",
    "JournalTail",
    "acting_door",
    "append",
    "current_door",
    "journal_path",
    "read_journal",
    "record_start",
]

JOURNAL_MAX_BYTES = 2 << 20  # past this the older half is dropped (a lab's worth is ~100 kB)

_door: contextvars.ContextVar[str] = contextvars.ContextVar("course_door", default="Python")


def current_door() -> str:
    """Return the door the current parameter request comes through (`%ros2`, `terminal`...)."""
    return _door.get()


@contextlib.contextmanager
def acting_door(name: str) -> Iterator[None]:
    """Tag the parameter requests made inside the block as coming through door `name`."""
    token = _door.set(name)
    try:
        yield
    finally:
        _door.reset(token)


def journal_path(domain: int | str) -> Path:
    """Return the journal file of ROS domain `domain`."""
    return runtime_dir() / f"param-journal-{int(domain)}.jsonl"


def _trim(handle: int, path: Path) -> None:
    """Keep the newer half of an overlong journal (called with the lock held)."""
    size = os.fstat(handle).st_size
    if size <= JOURNAL_MAX_BYTES:
        return
    with open(path, "rb") as source:
        source.seek(size - JOURNAL_MAX_BYTES // 2)
        tail = source.read().split(b"\n", 1)[-1]
    os.ftruncate(handle, 0)
    os.write(handle, tail)


def append(domain: int | str | None, record: dict[str, Any]) -> None:
    """Append one record (stamped with the wall time and pid) to the domain's journal.

    Never raises for I/O: a journal that cannot be written costs the history an entry, not
    the learner their command.
    """
    if domain is None or str(domain).strip() == "":
        return
    line = {"wall": time.time(), "pid": os.getpid(), **record}
    data = (json.dumps(line, separators=(",", ":"), default=str) + "\n").encode()
    try:
        path = journal_path(domain)
        fd = os.open(path, os.O_RDWR | os.O_APPEND | os.O_CREAT, 0o600)
    except OSError:
        return
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        _trim(fd, path)
        size = os.fstat(fd).st_size
        if size and os.pread(fd, 1, size - 1) != b"\n":
            data = b"\n" + data  # a writer died mid-line: its torn line stays alone
        os.write(fd, data)
    except OSError:
        pass
    finally:
        os.close(fd)  # closing releases the lock


def _records(raw: bytes) -> list[dict[str, Any]]:
    records = []
    for line in raw.splitlines():
        with contextlib.suppress(ValueError):
            record = json.loads(line)
            if isinstance(record, dict):
                records.append(record)
    return records


def read_journal(domain: int | str) -> list[dict[str, Any]]:
    """Return the domain's records, oldest first (unreadable lines skipped)."""
    try:
        raw = journal_path(domain).read_bytes()
    except OSError:
        return []
    return _records(raw)


class JournalTail:
    """Read a domain's journal as it grows: each `read` returns only the records appended
    since the last one (the first, those of the last `start_bytes`), so that a reader that
    keeps up costs a few lines per read. When the file was cut (`_trim`) or replaced since,
    `read` starts over."""

    def __init__(self, domain: int | str, *, start_bytes: int | None = None) -> None:
        self._domain = domain
        self._start_bytes = start_bytes
        self._offset = 0
        self._last_line = b""  # the whole line that ends at `_offset`: it is still there?

    def read(self) -> tuple[list[dict[str, Any]], bool]:
        """Return the new records, oldest first, and whether the reading started over (the
        records read before are no longer all in the file: forget them)."""
        had_read = self._offset > 0
        try:
            with open(journal_path(self._domain), "rb") as handle:
                if not self._continues(handle):
                    self._offset, self._last_line = 0, b""
                restarted = had_read and self._offset == 0
                if not self._offset:
                    self._offset = self._start(handle)
                handle.seek(self._offset)
                data = handle.read()
        except OSError:  # no journal (yet, or any more)
            self._offset, self._last_line = 0, b""
            return [], had_read
        whole = data[: data.rfind(b"\n") + 1]  # a line being written is read next time
        if whole:
            self._offset += len(whole)
            self._last_line = whole[whole.rfind(b"\n", 0, len(whole) - 1) + 1 :]
        return _records(whole), restarted

    def _start(self, handle: Any) -> int:
        """Return where a first read starts: the first whole line of the last `start_bytes`."""
        size = os.fstat(handle.fileno()).st_size
        if self._start_bytes is None or size <= self._start_bytes:
            return 0
        handle.seek(size - self._start_bytes - 1)
        return int(handle.tell()) + len(handle.readline())

    def _continues(self, handle: Any) -> bool:
        if not self._offset:
            return True
        size = os.fstat(handle.fileno()).st_size
        if size < self._offset:
            return False
        mark = os.pread(handle.fileno(), len(self._last_line), self._offset - len(self._last_line))
        return mark == self._last_line


def record_start(
    domain: int | str | None,
    executable: str,
    argv: list[str],
    *,
    cwd: str | None,
    pid: int | None = None,
) -> None:
    """Record that a course door starts `executable` with `argv` (its `--ros-args` matter),
    as process `pid` when the door knows it and learns no node name from the log."""
    ros_args = argv[argv.index("--ros-args") + 1 :] if "--ros-args" in argv else []
    record = {
        "t": "start",
        "door": current_door(),
        "exe": executable,
        "args": ros_args,
        "cwd": cwd or os.getcwd(),
    }
    append(domain, record if pid is None else {**record, "pid": pid})
