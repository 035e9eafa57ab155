"""How the suite deals its files to xdist's workers, from a table measured in a whole run
(`tests/file_seconds.txt`: each file's seconds and CPU-seconds).

Longest first: each worker takes whole files (`--dist loadfile`), so a long file dealt last
keeps one worker busy while the others stand idle (a run here ended with one worker alone for
90 s on the three slowest one-test files, which xdist's own order, by test count, deals last).

One worker for the files that wait: some files spend their time waiting on real time (a
robot driven for a grading window, a command that prints each second until Ctrl-C, an idle
kernel measured), using a tenth of a core or less. Dealt among the others, several of them
ran at once now and then, and the cores stood idle (ci106: 85.9% busy over the run, a third
idle in its dips). They form one unit of work instead (`scope_of`), dealt first to a worker
of its own beside the workers that use the cores: four runs 93-95% busy, pytest's time
489-514 s, against 515-536 s the same day without it.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

from course_lib.core.atomic_files import atomic_write

__all__ = [
    "SECONDS_FILE",
    "WAITING_LANE",
    "FileFigures",
    "deal_order",
    "file_of",
    "read_figures",
    "scope_of",
    "waiting_lane",
    "write_figures",
]

SECONDS_FILE = Path(__file__).resolve().parents[1] / "file_seconds.txt"
_HEADER = """\
# Each test file's seconds and CPU-seconds (with every process it started) in a whole run
# (`make test` on 2 cores): the suite deals the files longest first, and those that mostly
# wait to a worker of their own (tests/support/file_order.py). Files not listed count as 0.
# Written by `COURSE_FILE_SECONDS=tests/file_seconds.txt make test`.
"""
WAITING_LANE = "the files that wait"  # xdist's name for their unit of work
WAITING_SHARE = 0.15  # a file that waits uses less than this share of a core over its run
# The lane holds at most this share of what each worker runs, so it never ends the run last.
LANE_SHARE = 0.8


@dataclass(frozen=True)
class FileFigures:
    """One file's figures in the measured run (cpu None: not measured)."""

    seconds: float
    cpu: float | None = None

    @property
    def waits(self) -> bool:
        """Whether the file mostly waits on real time rather than using a core."""
        return self.cpu is not None and self.cpu < WAITING_SHARE * self.seconds


class _Item(Protocol):
    nodeid: str


def file_of(nodeid: str) -> str:
    """Return the file part of a test's node id (pure)."""
    return nodeid.split("::", 1)[0]


def read_figures(path: Path = SECONDS_FILE) -> dict[str, FileFigures]:
    """Return {file: figures} from the table ('' lines and # comments skipped)."""
    figures: dict[str, FileFigures] = {}
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        parts = line.split(maxsplit=2)
        try:
            seconds, cpu, name = float(parts[0]), parts[1], parts[2]
            figures[name] = FileFigures(seconds, None if cpu == "-" else float(cpu))
        except (ValueError, IndexError):
            raise ValueError(
                f"{path}:{number}: expected 'SECONDS CPU-SECONDS FILE' (CPU '-' if not "
                f"measured), got {line!r}"
            ) from None
    return figures


def write_figures(
    seconds: Mapping[str, float], cpu: Mapping[str, float], path: Path, *, at_least: float = 2.0
) -> None:
    """Write the files that took `at_least` seconds, longest first, with their CPU-seconds
    ('-' where none was measured); whole or not at all: every collection reads this file."""
    rows = sorted(((s, f) for f, s in seconds.items() if s >= at_least), reverse=True)
    lines = [f"{s:.0f} {cpu[f]:.1f} {f}\n" if f in cpu else f"{s:.0f} - {f}\n" for s, f in rows]
    atomic_write(path, _HEADER + "".join(lines))


def waiting_lane(figures: Mapping[str, FileFigures], workers: int) -> frozenset[str]:
    """Return the files that mostly wait, longest first, as long as together they take at
    most LANE_SHARE of what each of `workers` runs (pure)."""
    if workers < 2:
        return frozenset()
    most = LANE_SHARE * sum(f.seconds for f in figures.values()) / workers
    lane: set[str] = set()
    total = 0.0
    for name, figure in sorted(figures.items(), key=lambda pair: -pair[1].seconds):
        if figure.waits and total + figure.seconds <= most:
            lane.add(name)
            total += figure.seconds
    return frozenset(lane)


def scope_of(nodeid: str, lane: Collection[str]) -> str:
    """Return a test's unit of work: its file, or the waiting lane's if its file is in it."""
    name = file_of(nodeid)
    return WAITING_LANE if name in lane else name


def deal_order(
    items: Sequence[_Item],
    seconds: Mapping[str, float],
    *,
    late: Collection[str] = (),
    workers: int = 1,
    lane: Collection[str] = (),
) -> list[_Item]:
    """Return `items` with their files in the order they are dealt (pure; a file's own tests
    keep their order; files not listed keep theirs, after the listed ones): the waiting lane's
    files first (one unit, one worker), then the others longest first.

    A file in `late` waits at its start for something the run begins at collection (the class
    hub's learners' environment, about 80 s): it is dealt no earlier than the second round, so
    it starts after a worker's first file instead of standing idle at the run's start (ci95: a
    worker waited 75 s for the build); in the lane, it goes last. xdist deals each worker two
    files at once, and the first round is the first file of each."""
    first: dict[str, int] = {}
    for place, item in enumerate(items):
        first.setdefault(file_of(item.nodeid), place)
    files = sorted(first, key=lambda name: (-seconds.get(name, 0.0), first[name]))
    waiting = [name for name in files if name in lane]
    waiting.sort(key=lambda name: name in late)  # stable: longest first otherwise
    others = [name for name in files if name not in lane]
    opening = [name for name in others if name not in late][: workers - (1 if waiting else 0)]
    files = waiting + opening + [name for name in others if name not in opening]
    rank = {name: place for place, name in enumerate(files)}
    return sorted(items, key=lambda item: rank[file_of(item.nodeid)])
