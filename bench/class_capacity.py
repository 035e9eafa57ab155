"""How many learners one host holds: N labs, each running lesson 7's drive at the same time.

Run: .venv/bin/python -m bench.class_capacity [--max 16] [--window 30] [--gets 30]
     [--idle N] [--keep-going] [--only N] [--record]
A learner is what a learner's server runs: a lab as `make lab` starts it (JupyterLab, the lab's
machine service, the world: MuJoCo simulation and meshcat view; no terminal, so no ros2
daemon, which starts with a lab's first terminal) and a real
kernel running lesson 7's cells (start(7), world, `%ros2 run parameter_tests param_vel`,
the live speed plot, `%ros2 param set ... velocity 0.2`, the drive), plus one websocket client
per learner on the 3D view through JupyterLab's proxy (the learner's browser tab). For N = 1,
2, 4, 8, ... all N
learners drive at once; over a common window each kernel measures its simulation's real-time
factor (the /odom stamps against wall time) and times `%ros2 param get` magics, one in each
equal slot of the window at a random moment of it, one a second by default (a learner types
slower; the bench's 200 in 30 s cost each kernel 0.02 cores, a seventh of a driving learner,
so the probe measured its own load) (--in-step: at the slot's start, every
learner's at the same instant; learners do not type in step, and N gets at once measure a
burst: N x 2 ms of CPU on 2 cores).
Each round prints every learner's figures and one learner's processes (CPU cores, PSS MiB);
the end says which goal fails first as learners are added, and from which N on memory per
learner is within its goal (it falls as learners share the libraries).
--idle N adds N idle learners beside the driving ones, from the first round on: lesson 7's
first cells run, the velocity at 0, no 3D view watched, no cell running (a learner reading).
Each round prints one idle learner's processes apart, and their cores beside the tutorial's
own node (which ticks ten times a second by design) against the idle goal (<= 0.005 cores).
The bench adds learners until a goal fails (--keep-going: until the real-time factor fails;
at most --max), then stops everything it started, also on Ctrl-C or SIGTERM. A failed round
is measured again (up to three times) when processes outside the bench used the CPU.
--record writes the figures to deploy/capacity.yaml (the Kubernetes requests come from there).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import signal
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import psutil

from bench._capacity_report import (
    RTF_GOAL,
    Figures,
    Round,
    Usage,
    judge,
    kept_attempt,
    measure_again,
    print_class,
    print_processes,
    print_round,
    record,
    summary,
)
from bench._labs import Lab, LabKernel, start_lab, tree_pids
from course_lib.core.host.procfs import environ as process_environ
from course_lib.processes.orphans import NAME_ENV

HUB = -1  # the hub's own processes, measured beside the learners' (bench.hub_class)
GETS_PER_S = 1.0  # each learner's param gets a second of the window, unless --gets says
OTHERS_LIMIT = 0.25  # cores used outside the bench that make a failed round suspect
ATTEMPTS = 3

# Lesson 7's cells (notebooks/07_move_the_robot.ipynb), up to the drive.
SETUP = [
    "from course_lib.lessons import start\n\nlesson = start(7)",
    "world = lesson.world()",
    "%ros2 run parameter_tests param_vel",
    "plot = lesson.speed_plot()",  # the live speed plot stays on (the p99 goal is with it)
    "print('viewer port', world.viewer.port)",
]
# An idle learner: the same first cells (no plot), the robot left still (bench.idle_lab's lab).
IDLE_SETUP = [*SETUP[:3], "%ros2 param set /param_vel_node velocity 0.0"]
DRIVE = """\
%ros2 param set /param_vel_node velocity 0.2
lesson.drive_for(3.0)
from bench._capacity_kernel import drive_window
print('window', drive_window(lesson, {t0!r}, {t1!r}, {gets}, {seed!r}))
%ros2 param set /param_vel_node velocity 0.0
lesson.wait_until_stopped()
world.reset()
"""


@dataclass
class Learner:
    """One learner's lab, kernel and 3D view port."""

    number: int
    lab: Lab
    kernel: LabKernel
    viewer_port: int = 0
    view_updates: int = 0

    @property
    def roots(self) -> list[int]:
        return [self.lab.pid, self.kernel.pid]

    def view_request(self) -> str:
        """Return the address of the 3D view's websocket, through the lab's proxy."""
        lab = self.lab
        return f"ws://127.0.0.1:{lab.port}/proxy/{self.viewer_port}/?token={lab.token}"

    def stop(self) -> None:
        try:
            self.kernel.shutdown()
        finally:
            self.lab.stop()


# --- measuring the host -------------------------------------------------------------------
def _cpu_seconds(pids: list[int]) -> dict[int, float]:
    seconds = {}
    for pid in pids:
        try:
            times = psutil.Process(pid).cpu_times()
            seconds[pid] = times.user + times.system
        except psutil.NoSuchProcess:
            continue
    return seconds


def _pss_mib(pids: list[int]) -> dict[int, float]:
    """Return the PSS (RSS where PSS is unavailable) of each of `pids` in MiB."""
    sizes = {}
    for pid in pids:
        try:
            info = psutil.Process(pid).memory_full_info()
            sizes[pid] = getattr(info, "pss", info.rss) / 2**20
        except (psutil.NoSuchProcess, psutil.AccessDenied):
            continue
    return sizes


def _label(pid: int) -> str:
    """Return a short name for a learner's process: the course's name for it, else its command."""
    try:
        command = " ".join(psutil.Process(pid).cmdline())
    except psutil.NoSuchProcess:
        return "gone"
    if "-m course_lib lab" in command or "-m course_lib hub-lab" in command:
        return "lab (machine service)"
    if "kernel_launcher" in command:  # ipykernel_launcher, the course's kernel_launcher
        return "kernel"
    name = process_environ(pid).get(NAME_ENV)
    if name:
        return name.rsplit("-", 1)[0] if name.startswith("ros2-daemon-") else name  # one per lab
    return " ".join(Path(a).name for a in command.split()[:3])[:40]


def shm_mib(pids: list[int]) -> float:
    """Return the size of the distinct /dev/shm files `pids` map (Fast DDS segments), MiB."""
    files: set[str] = set()
    for pid in pids:
        try:
            maps = Path(f"/proc/{pid}/maps").read_text()
        except OSError:
            continue
        files.update(line.split(None, 5)[5] for line in maps.splitlines() if " /dev/shm/" in line)
    total = 0
    for name in files:
        try:
            total += os.stat(name).st_size
        except OSError:
            continue
    return total / 2**20


def _busy_seconds() -> float:
    times = psutil.cpu_times()
    return times.user + times.nice + times.system + times.irq + times.softirq + times.steal


# --- the learners' 3D views ----------------------------------------------------------------
class Views:
    """One websocket client per learner on its 3D view, through its JupyterLab's proxy."""

    def __init__(self) -> None:
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, daemon=True)
        self.thread.start()
        self.tasks: list[object] = []

    def watch(self, learner: Any) -> None:
        """Count `learner`'s view updates (anything with `view_request()`, `view_updates`)."""
        future = asyncio.run_coroutine_threadsafe(self._count(learner), self.loop)
        self.tasks.append(future)

    async def _count(self, learner: Any) -> None:
        import tornado.websocket

        connection = await tornado.websocket.websocket_connect(learner.view_request())
        while True:
            message = await connection.read_message()
            if message is None:
                return
            if isinstance(message, bytes) and b"/meshcat/mujoco/base_link" in message:
                learner.view_updates += 1

    def stop(self) -> None:
        for task in self.tasks:
            task.cancel()  # type: ignore[attr-defined]
        self.loop.call_soon_threadsafe(self.loop.stop)
        self.thread.join(5.0)


# --- one round -----------------------------------------------------------------------------
def add_learner(number: int, views: Views | None) -> Learner:
    """Start a lab and a kernel, run lesson 7's first cells; return the learner (a driving
    one watches its 3D view; an idle one, `views` None, leaves the robot still)."""
    lab = start_lab(class_host=True)  # the bench's host stands for a class's
    try:
        kernel = LabKernel(lab)
    except BaseException:
        lab.stop()
        raise
    learner = Learner(number, lab, kernel)
    try:
        if views is None:
            for cell in IDLE_SETUP:
                kernel.collect(kernel.submit(cell), timeout=120.0)
            return learner
        for cell in SETUP:
            printed = kernel.collect(kernel.submit(cell), timeout=120.0)
        learner.viewer_port = int(printed.split()[-1])
        views.watch(learner)
    except BaseException:
        learner.stop()
        raise
    return learner


def _usage(
    pids: list[int],
    used: dict[int, float],
    pss: dict[int, float],
    labels: dict[int, str],
    elapsed: float,
) -> dict[str, tuple[float, float]]:
    """Return cores and MiB by process label for one learner's processes."""
    by_process: dict[str, tuple[float, float]] = {}
    for pid in pids:
        label = labels.get(pid, "gone")
        cores, mib = by_process.get(label, (0.0, 0.0))
        by_process[label] = (cores + used.get(pid, 0.0) / elapsed, mib + pss.get(pid, 0))
    return by_process


def drive_round(
    learners: list[Any],
    window_s: float,
    gets: int,
    *,
    in_step: bool = False,
    idle: list[Learner] | None = None,
    hub: dict[int, str] | None = None,
) -> Round:
    """Let every learner drive at once; measure the common window; return the figures (each
    learner's gets at its own random moments, or all learners' at the same instants; the
    `idle` learners' usage apart; the `hub`'s processes, pid to label, apart too)."""
    idle = idle or []
    hub = hub or {}
    lead = 15.0 + 2.0 * len(learners)  # param set + drive_for(3.0) everywhere before t0
    t0 = time.time() + lead
    t1 = t0 + window_s
    ids = [
        learner.kernel.submit(
            DRIVE.format(t0=t0, t1=t1, gets=gets, seed=None if in_step else learner.number)
        )
        for learner in learners
    ]
    time.sleep(max(0.0, t0 - time.time()))
    bench_late = max(0.0, time.time() - t0)
    own = os.getpid()
    roots = {learner.number: tree_pids(learner.roots) for learner in [*learners, *idle]}
    roots[HUB] = list(hub)
    before = {n: _cpu_seconds(pids) for n, pids in roots.items()}
    labels = {pid: hub.get(pid) or _label(pid) for pids in roots.values() for pid in pids}
    bench_before, busy_before = _cpu_seconds([own])[own], _busy_seconds()
    views_before = {learner.number: learner.view_updates for learner in learners}
    started = time.monotonic()
    time.sleep(max(0.0, t1 - time.time()))
    elapsed = time.monotonic() - started
    after = {n: _cpu_seconds(pids) for n, pids in roots.items()}
    bench_cpu = _cpu_seconds([own])[own] - bench_before
    busy = (_busy_seconds() - busy_before) / elapsed
    load = os.getloadavg()
    # After the window: reading a process's smaps_rollup walks its memory under the lock its
    # own mmap and munmap take, and 100 of them take seconds: the gets it stalled were timed.
    pss = {n: _pss_mib(pids) for n, pids in roots.items()}
    shm = {learner.number: shm_mib(roots[learner.number]) for learner in learners}
    mem_used = (psutil.virtual_memory().total - psutil.virtual_memory().available) / 2**20
    figures = []
    learners_cpu = 0.0
    for learner in learners:
        printed = learner.kernel.collect(ids[learners.index(learner)], timeout=window_s + 120)
        line = next(ln for ln in printed.splitlines() if ln.startswith("window "))
        data = json.loads(line.removeprefix("window "))
        n = learner.number
        used = {pid: after[n][pid] - before[n][pid] for pid in after[n] if pid in before[n]}
        cpu = sum(used.values())
        learners_cpu += cpu
        by_process = _usage(roots[n], used, pss[n], labels, elapsed)
        views = learner.view_updates - views_before[n]
        figures.append(
            Figures(
                rtf=data["rtf"],
                gets_ms=[g * 1e3 for g in data["gets_s"]],
                top_speed=data["top_speed"],
                late_s=data["late_s"],
                cpu_cores=cpu / elapsed,
                pss_mib=sum(pss[n].values()),
                shm_mib=shm[n],
                views_per_s=views / elapsed,
                by_process=by_process,
            )
        )
    idle_usage = []
    for learner in idle:
        n = learner.number
        used = {pid: after[n][pid] - before[n][pid] for pid in after[n] if pid in before[n]}
        learners_cpu += sum(used.values())
        idle_usage.append(Usage(_usage(roots[n], used, pss[n], labels, elapsed)))
    used = {pid: after[HUB][pid] - before[HUB][pid] for pid in after[HUB] if pid in before[HUB]}
    learners_cpu += sum(used.values())
    hub_usage = Usage(_usage(roots[HUB], used, pss[HUB], labels, elapsed)) if hub else None
    others = busy - (learners_cpu + bench_cpu) / elapsed
    result = Round(
        figures,
        elapsed,
        busy,
        others,
        load,
        mem_used,
        idle=idle_usage,
        hub=hub_usage,
        bench_late_s=bench_late,
    )
    result.failures = judge(figures)
    return result


def measured_round(drive: Callable[[], Round], others_limit: float) -> Round:
    """Drive one round and print it; measure it again (up to ATTEMPTS) while its failures may
    not be the class's own (`measure_again`); print and return the attempt kept."""
    attempts: list[Round] = []
    for attempt in range(1, ATTEMPTS + 1):
        attempts.append(drive())
        print_round(attempts[-1])
        why = measure_again(attempts[-1], others_limit)
        if why is None:
            break
        if attempt < ATTEMPTS:
            print(f"  {why}: measured again")
            wait_for_quiet(others_limit)
    kept = min(attempts, key=kept_attempt)
    if len(attempts) > 1:
        print(f"  N = {kept.n}: kept the attempt with others at {kept.others_cores:.2f}")
    print_processes(kept)
    return kept


def wait_for_quiet(limit: float, patience_s: float = 60.0) -> None:
    """Wait (up to `patience_s`) until processes outside the bench use under `limit` cores."""
    deadline = time.monotonic() + patience_s
    while time.monotonic() < deadline:
        pids = [*tree_pids([os.getpid()]), os.getpid()]  # the bench, its labs and kernels
        before, busy_before, t = _cpu_seconds(pids), _busy_seconds(), time.monotonic()
        time.sleep(5.0)
        after, elapsed = _cpu_seconds(pids), time.monotonic() - t
        ours = sum(after[pid] - before[pid] for pid in after if pid in before)
        if (_busy_seconds() - busy_before - ours) / elapsed < limit:
            return


def sizes(cap: int) -> list[int]:
    """Return 1, 2, 4, ... up to `cap` (pure)."""
    out, n = [], 1
    while n <= cap:
        out.append(n)
        n *= 2
    return out


def planned_sizes(cap: int, only: int | None) -> list[int]:
    """Return the N the bench measures: `only` alone, else `sizes(cap)` (pure)."""
    return [only] if only else sizes(cap)


def gets_timing(in_step: bool, gets: int, window_s: float) -> str:
    """Say when the learners' param gets come and how often (pure)."""
    when = (
        "every learner's at the same instants (--in-step)"
        if in_step
        else "each learner's at its own random moments"
    )
    return f"{when}, {gets / window_s:.2g} a second ({gets} in {window_s:g} s)"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max", type=int, default=16, help="most learners (default 16)")
    parser.add_argument("--window", type=float, default=30.0, help="seconds measured per N")
    parser.add_argument(
        "--gets", type=int, default=None, help="param gets per learner per N (one a second)"
    )
    parser.add_argument(
        "--in-step",
        action="store_true",
        help="every learner's param gets at the same instants (a burst of N commands at once; "
        "by default each learner's come at its own random moments, as people type)",
    )
    parser.add_argument(
        "--idle",
        type=int,
        default=0,
        help="idle learners beside the driving ones (lesson 7's first cells, the robot still)",
    )
    parser.add_argument(
        "--only",
        type=int,
        default=None,
        help="measure this one N (a quicker check; not with --record, which needs every N)",
    )
    parser.add_argument("--record", action="store_true", help="write deploy/capacity.yaml")
    parser.add_argument(
        "--keep-going",
        action="store_true",
        help="after a failed latency goal, add learners until the real-time factor fails",
    )
    parser.add_argument(
        "--others",
        type=float,
        default=OTHERS_LIMIT,
        help="a failed round is measured again if processes outside the bench used more "
        f"cores than this (default {OTHERS_LIMIT})",
    )
    args = parser.parse_args()
    if args.only is not None and args.record:
        parser.error("--record needs every N: leave out --only")
    gets = args.gets or max(1, round(args.window * GETS_PER_S))
    signal.signal(signal.SIGTERM, signal.default_int_handler)  # stop everything on SIGTERM too
    started = time.monotonic()
    load_before = os.getloadavg()
    print(
        f"{os.cpu_count()} cores, {psutil.virtual_memory().total / 2**30:.1f} GiB; load average "
        f"{load_before[0]:.2f} {load_before[1]:.2f} {load_before[2]:.2f} before the bench",
        flush=True,
    )
    print(f"param gets: {gets_timing(args.in_step, gets, args.window)}", flush=True)
    learners: list[Learner] = []
    idle: list[Learner] = []
    rounds: list[Round] = []
    views = Views()
    try:
        while len(idle) < args.idle:
            idle.append(add_learner(1000 + len(idle), None))
        for n in planned_sizes(args.max, args.only):
            while len(learners) < n:
                learners.append(add_learner(len(learners) + 1, views))
            rounds.append(
                measured_round(
                    lambda: drive_round(
                        learners, args.window, gets, in_step=args.in_step, idle=idle
                    ),
                    args.others,
                )
            )
            if rounds[-1].failures and not (args.keep_going and rounds[-1].rtf_min >= RTF_GOAL):
                break
    finally:
        views.stop()
        for learner in reversed([*learners, *idle]):
            learner.stop()
    if not rounds:
        raise SystemExit("no round finished")
    facts = summary(rounds)
    print_class(facts, load_before, time.monotonic() - started)
    if args.record:
        record(facts, load_before, gets_timing(args.in_step, gets, args.window))


if __name__ == "__main__":
    main()
