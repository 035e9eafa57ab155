"""The CPU each test used, with every process it started (a lab, a browser, a kernel, ...).

The suite is CPU-bound on 2 cores, so its time is the sum of what its tests make the machine
do, and most of that is in child processes that outlive a wait or are re-parented (chromium,
a simulation), which `getrusage` never counts. Each test process moves itself into a cgroup
of its own as it starts; everything it starts is then in it, and the cgroup's CPU usage before
and after a test is what that test cost. Where no cgroup can be made (not root, no cgroupfs),
nothing is measured and the summary says why.

Each test's figure is a line of `test-artifacts/cpu/<pid>.jsonl`; the run's controller sums
them by file at the end (`summary`). Work that is no test's, such as a build started at
collection, is counted apart (`count_apart`), under a name of its own.
"""

from __future__ import annotations

import contextlib
import json
import os
import threading
import time
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from file_order import file_of

__all__ = ["CpuMeter", "count_apart", "read_records", "record", "summary"]

_V1 = Path("/sys/fs/cgroup/cpuacct")
_UNIFIED = (Path("/sys/fs/cgroup"), Path("/sys/fs/cgroup/unified"))
_PREFIX = "course-tests-"
_counting: CpuMeter | None = None  # this process's meter, once it measures


@dataclass
class _Apart:
    """A process counted apart from the tests, in a cgroup of its own."""

    name: str
    folder: Path
    since: float
    ended: float | None = None  # when its cgroup was first seen empty

    def watch(self, period_s: float = 1.0) -> None:
        """Note when the cgroup empties, looking every `period_s` (run in a daemon thread)."""
        while self.ended is None:
            try:
                empty = not (self.folder / "cgroup.procs").read_text().strip()
            except OSError:  # removed: the meter was closed
                return
            if empty:
                self.ended = time.monotonic()
                return
            time.sleep(period_s)


def _own_cgroups() -> list[tuple[Path, str]]:
    """Return this process's cgroup folders that count CPU (cgroup v1's cpuacct, then v2),
    each with its usage file. A cgroup made inside one of them is counted in it as well, so a
    pytest run started by a test (in a cgroup of its own) still counts in that test."""
    try:
        lines = Path("/proc/self/cgroup").read_text().splitlines()
    except OSError:
        return []
    found = []
    for line in lines:
        _id, controllers, path = line.split(":", 2)
        if "cpuacct" in controllers.split(","):
            found.append((_V1 / path.lstrip("/"), "cpuacct.usage"))
        elif line.startswith("0::"):
            found += [
                (root / path.lstrip("/"), "cpu.stat")
                for root in _UNIFIED
                if (root / "cgroup.controllers").exists()
            ]
    return sorted(found, key=lambda pair: pair[1] != "cpuacct.usage")


class CpuMeter:
    """Move this process into a cgroup of its own and read the CPU it and its children used."""

    def __init__(self) -> None:
        global _counting
        self.folder: Path | None = None
        self.problem = ""
        self._usage_file = ""
        self._apart: list[_Apart] = []
        for parent, usage in _own_cgroups():
            if not (parent / "cgroup.procs").exists():
                continue
            _remove_empty_leftovers(parent)
            folder = parent / f"{_PREFIX}{os.getpid()}"
            try:
                folder.mkdir(exist_ok=True)
                (folder / "cgroup.procs").write_text(str(os.getpid()))
            except OSError as error:
                self.problem = f"cannot use a cgroup in {parent}: {error}"
                continue
            self.folder, self._usage_file, self.problem = folder, usage, ""
            _counting = self
            return
        self.problem = self.problem or "no cgroup filesystem here"

    def seconds(self) -> float:
        """Return the CPU seconds this cgroup has used so far (0.0 when not measuring)."""
        return 0.0 if self.folder is None else self._usage(self.folder)

    def _usage(self, folder: Path) -> float:
        text = (folder / self._usage_file).read_text()
        if self._usage_file == "cpuacct.usage":
            return int(text) / 1e9
        fields = dict(line.split() for line in text.splitlines())
        return int(fields["usage_usec"]) / 1e6

    def count_apart(self, pid: int, name: str, *, watch_period_s: float = 1.0) -> None:
        """Count process `pid`, and whatever it starts from now on, as `name` in a cgroup
        beside this one, so that no test is charged with it (its end is looked for every
        `watch_period_s`); where that cannot be done, it stays counted in the test that runs
        meanwhile."""
        if self.folder is None:
            return
        folder = self.folder.parent / f"{_PREFIX}{pid}"
        try:
            folder.mkdir(exist_ok=True)
            (folder / "cgroup.procs").write_text(str(pid))
        except OSError:
            return
        entry = _Apart(name, folder, time.monotonic())
        self._apart.append(entry)
        watch = threading.Thread(
            target=entry.watch, args=(watch_period_s,), name=f"cpu-apart-{pid}", daemon=True
        )
        watch.start()

    def apart(self) -> list[tuple[str, float, float]]:
        """Return the name, CPU seconds and wall seconds (until it ended, to within a watch
        period, or so far) of what is counted apart; a cgroup that is gone (another run's
        clean-up took it once empty) is left out rather than failing the run's end."""
        now, figures = time.monotonic(), []
        for entry in self._apart:
            with contextlib.suppress(OSError):
                cpu = self._usage(entry.folder)
                figures.append((entry.name, cpu, (entry.ended or now) - entry.since))
        return figures

    def close(self) -> None:
        """Move this process back to the parent cgroup; remove this one and those counted
        apart once nothing is in them (a process left running keeps its cgroup, and the next
        run removes it when empty)."""
        global _counting
        if self.folder is None:
            return
        with contextlib.suppress(OSError):
            (self.folder.parent / "cgroup.procs").write_text(str(os.getpid()))
            self.folder.rmdir()
        for entry in self._apart:
            with contextlib.suppress(OSError):
                entry.folder.rmdir()
        self.folder, self._apart = None, []
        if _counting is self:
            _counting = None


def count_apart(pid: int, name: str) -> None:
    """Count process `pid` under `name` (a test id's form, `file::what`) instead of in the
    tests of this process; nothing happens where nothing is measured."""
    if _counting is not None:
        _counting.count_apart(pid, name)


def _remove_empty_leftovers(parent: Path) -> None:
    """Remove the cgroups that earlier runs left in `parent` once their processes are gone,
    innermost first: a run's workers' cgroups sit inside its controller's, and a worker's
    still holds the processes its tests started when the worker ends."""
    for old in parent.glob(f"{_PREFIX}*"):
        if old.is_dir():
            _remove_empty_leftovers(old)
            with contextlib.suppress(OSError):  # only an empty cgroup goes: a busy one stays
                old.rmdir()


def record(folder: Path, nodeid: str, cpu_s: float, wall_s: float) -> None:
    """Append one test's figures to this process's file in `folder`."""
    folder.mkdir(parents=True, exist_ok=True)
    line = json.dumps({"test": nodeid, "cpu_s": round(cpu_s, 2), "wall_s": round(wall_s, 2)})
    with (folder / f"{os.getpid()}.jsonl").open("a", encoding="utf-8") as out:
        out.write(line + "\n")


def read_records(folder: Path) -> list[dict[str, object]]:
    """Return every test's figures written in `folder` (a torn last line is skipped)."""
    records = []
    for path in sorted(folder.glob("*.jsonl")):
        for line in path.read_text(encoding="utf-8").splitlines():
            try:
                records.append(json.loads(line))
            except json.JSONDecodeError:
                continue
    return records


def summary(records: Iterable[dict[str, object]], top: int = 12) -> list[str]:
    """Return the lines of the end-of-run table: the files that used the most CPU, then the
    total and each top folder's share (pure)."""
    by_file: dict[str, list[float]] = {}
    by_folder: dict[str, float] = {}
    for row in records:
        name = file_of(str(row["test"]))
        cpu, wall = float(row["cpu_s"]), float(row["wall_s"])  # type: ignore[arg-type]
        figures = by_file.setdefault(name, [0.0, 0.0])
        figures[0] += cpu
        figures[1] += wall
        parts = name.split("/")
        folder = "/".join(parts[:2]) if parts[0] == "tests" and len(parts) > 2 else parts[0]
        by_folder[folder] = by_folder.get(folder, 0.0) + cpu
    total = sum(by_folder.values())
    if not total:
        return []
    lines = [f"{'CPU-s':>8} {'wall-s':>8}  file"]
    ranked = sorted(by_file.items(), key=lambda item: -item[1][0])
    lines += [f"{cpu:8.1f} {wall:8.1f}  {name}" for name, (cpu, wall) in ranked[:top]]
    shares = ", ".join(
        f"{name} {100 * cpu / total:.0f}%"
        for name, cpu in sorted(by_folder.items(), key=lambda item: -item[1])
    )
    lines.append(f"{total:8.1f} CPU-s in all ({len(by_file)} files): {shares}")
    return lines
