"""The suite's files, longest first: each worker takes whole files (`--dist loadfile`), so a
long file dealt last keeps one worker busy while the others stand idle (a run here ended with
one worker alone for 90 s on the three slowest one-test files, which xdist's own order, by
test count, deals last). The seconds come from a whole run (`tests/file_seconds.txt`)."""

from __future__ import annotations

from collections.abc import Collection, Sequence
from pathlib import Path
from typing import Protocol

from course_lib.core.files.atomic_files import atomic_write

__all__ = ["SECONDS_FILE", "file_of", "longest_first", "read_seconds", "write_seconds"]

SECONDS_FILE = Path(__file__).resolve().parents[1] / "file_seconds.txt"
_HEADER = """\
# Seconds each test file took in a whole run (`make test` on 2 cores): the suite
# deals the files longest first (tests/harness/file_order.py). Files not listed count as 0.
# Written by `COURSE_FILE_SECONDS=tests/file_seconds.txt make test`.
"""


class _Item(Protocol):
    nodeid: str


def file_of(nodeid: str) -> str:
    """Return the file part of a test's node id (pure)."""
    return nodeid.split("::", 1)[0]


def read_seconds(path: Path = SECONDS_FILE) -> dict[str, float]:
    """Return {file: seconds} from a seconds file ('' lines and # comments skipped)."""
    seconds: dict[str, float] = {}
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        value, _, name = line.partition(" ")
        try:
            seconds[name.strip()] = float(value)
        except ValueError:
            raise ValueError(f"{path}:{number}: expected 'SECONDS FILE', got {line!r}") from None
    return seconds


def write_seconds(seconds: dict[str, float], path: Path, *, at_least: float = 2.0) -> None:
    """Write the files that took `at_least` seconds, longest first (whole or not at all: every
    collection reads this file)."""
    rows = sorted(((s, f) for f, s in seconds.items() if s >= at_least), reverse=True)
    atomic_write(path, _HEADER + "".join(f"{s:.0f} {f}\n" for s, f in rows))


def longest_first(
    items: Sequence[_Item],
    seconds: dict[str, float],
    *,
    late: Collection[str] = (),
    workers: int = 1,
) -> list[_Item]:
    """Return `items` with their files ordered by `seconds`, longest first (pure; a file's own
    tests keep their order; files not listed keep theirs, after the listed ones).

    A file in `late` waits at its start for something the run begins at collection (the class
    hub's learners' environment, about 80 s): it is dealt no earlier than place `workers`, so
    it starts after a worker's first file instead of standing idle at the run's start (ci95: a
    worker waited 75 s for the build). xdist deals each worker two files at once, and the
    first `workers` places are the first file of each."""
    first: dict[str, int] = {}
    for place, item in enumerate(items):
        first.setdefault(file_of(item.nodeid), place)
    files = sorted(first, key=lambda name: (-seconds.get(name, 0.0), first[name]))
    opening = [name for name in files if name not in late][:workers]
    files = opening + [name for name in files if name not in opening]
    rank = {name: place for place, name in enumerate(files)}
    return sorted(items, key=lambda item: rank[file_of(item.nodeid)])
