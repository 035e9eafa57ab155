"""The lab's parameter journal: who asked for which parameter change, and what nodes reported.

One file per ROS domain (one lab, or one kernel outside a lab) in the user's private runtime
folder, readable by the learner only (0600). Every writer (a kernel, the terminal `ros2` and
its daemon, `ros2 launch`) appends one JSON line with a single `write` under an exclusive lock,
so lines of several processes never interleave and a crash leaves at most a line the reader
skips. It outlives kernels; `lesson.history()` reads it. Pure file code: no ROS.

Records (`"t"`): `set` (a course door is about to set a parameter: door, node, name, value,
old), `failed` (that set was refused), `event` (a /parameter_events message a kernel saw),
`start` (the course started a node: its `--ros-args`, from where; a terminal's `ros2 run` also
the pid, as its log goes to the terminal and the node's name is learnt from the graph),
`named` (a started process's node name, learnt from its log), `stopped` (a lesson's new driver
of the robot stopped another lesson's node: which node, who had started it, who stopped it and
for which node).
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


def read_journal(domain: int | str) -> list[dict[str, Any]]:
    """Return the domain's records, oldest first (unreadable lines skipped)."""
    try:
        raw = journal_path(domain).read_bytes()
    except OSError:
        return []
    records = []
    for line in raw.splitlines():
        with contextlib.suppress(ValueError):
            record = json.loads(line)
            if isinstance(record, dict):
                records.append(record)
    return records


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
