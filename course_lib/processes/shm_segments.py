"""The shared-memory segments that killed ROS processes leave in /dev/shm, and their removal.

Fast DDS's shared-memory transport gives each participant (each ROS process) a segment of its
own, `fastrtps_<16 hex digits>` (about 0.5 MiB), and holds an exclusive lock (flock) on the
empty file `fastrtps_<id>_el` beside it for as long as the participant lives. A participant
that ends cleanly removes both; one that is killed (a kernel killed with its nodes, a program
stopped with SIGKILL) never does. /dev/shm is memory: on a host that stays up the leftovers
add up, half a MiB for each participant killed (a pod's /dev/shm holds 256 MiB).

A segment is a leftover when nobody holds its lock and its lock file is older than a minute (a
participant locks the file it has just made at once; the minute spares one doing so now). Only
the current user's segments are touched. The shared port segments (`fastrtps_port<N>`, one per
port, reused by the next participant) are left alone, but for one its maker never finished
(its first word is not boost.interprocess's "initialized", 2, a minute on): every participant
that reaches that port waits for it forever (host-wide: each tries 7000, 7001, ... in turn),
and a lesson's `start()` hung in `rclpy.init` with the host idle.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import re
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

__all__ = ["SHM_DIR", "Swept", "sweep_stale_segments"]

SHM_DIR = Path("/dev/shm")
MIN_AGE_S = 60.0
_SEGMENT = re.compile(r"fastrtps_[0-9a-f]{16}")
_PORT = re.compile(r"fastrtps_port\d+")
_MADE = 2  # boost.interprocess's managed segment: its first word once the maker is done
_LOCK_SUFFIX = "_el"


@dataclass(frozen=True)
class Swept:
    """The leftover segments removed: how many, and how much memory they held."""

    segments: int = 0
    size_bytes: int = 0

    def sentence(self) -> str | None:
        """Return one sentence saying what was removed, or None if nothing was."""
        if not self.segments:
            return None
        mib = self.size_bytes / 2**20
        return (
            f"Removed {self.segments} shared-memory segment(s) ({mib:.1f} MiB) that killed ROS "
            "processes had left in /dev/shm."
        )


def sweep_stale_segments(
    folder: Path = SHM_DIR, *, min_age_s: float = MIN_AGE_S, now: float | None = None
) -> Swept:
    """Remove this user's Fast DDS segments in `folder` whose participant is gone."""
    now = time.time() if now is None else now
    try:
        names = [p.name for p in folder.iterdir()]  # one listing for both kinds
    except OSError:  # no /dev/shm here
        return Swept()
    removed: list[int | None] = []
    for name in names:
        if name.endswith(_LOCK_SUFFIX) and _SEGMENT.fullmatch(name.removesuffix(_LOCK_SUFFIX)):
            segment = folder / name.removesuffix(_LOCK_SUFFIX)
            removed.append(_remove_if_left(segment, folder / name, min_age_s, now))
        elif _PORT.fullmatch(name):
            removed.append(_remove_if_never_made(folder / name, min_age_s, now))
    sizes = [size for size in removed if size is not None]
    return Swept(len(sizes), sum(sizes))


@contextlib.contextmanager
def _own_old_file(path: Path, min_age_s: float, now: float) -> Iterator[tuple[int, int] | None]:
    """Open `path` (never through a symlink); yield its descriptor and size if it is this
    user's and at least `min_age_s` old, else None."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW)
    except OSError:
        yield None
        return
    try:
        info = os.fstat(fd)
        old = info.st_uid == os.getuid() and now - info.st_mtime >= min_age_s
        yield (fd, info.st_size) if old else None
    finally:
        os.close(fd)


def _remove_if_never_made(port: Path, min_age_s: float, now: float) -> int | None:
    """Remove a port segment its maker left unfinished; return its size, or None if kept."""
    with _own_old_file(port, min_age_s, now) as opened:
        if opened is None:
            return None
        fd, size = opened
        head = os.read(fd, 4)
        if len(head) == 4 and int.from_bytes(head, sys.byteorder) == _MADE:
            return None
        port.unlink(missing_ok=True)
        return size


def _remove_if_left(segment: Path, lock_file: Path, min_age_s: float, now: float) -> int | None:
    """Remove `segment` and its lock file if nobody holds the lock; return its size, or None."""
    with _own_old_file(lock_file, min_age_s, now) as opened:
        if opened is None:
            return None
        fd, _size = opened
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:  # held: its participant lives
            return None
        try:
            size: int | None = segment.stat().st_size
            segment.unlink()
        except FileNotFoundError:
            size = None  # a lock file alone: removed, not counted
        lock_file.unlink(missing_ok=True)  # while locked: no participant can take it meanwhile
        return size
