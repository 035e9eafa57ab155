"""How many learners one host holds: N labs, each running lesson 7's drive at the same time.

Run: .venv/bin/python -m bench.class_capacity [--max 16] [--window 30] [--gets 200] [--record]
A learner is what a learner's server runs: a lab as `make lab` starts it (JupyterLab, the lab's
machine service and ros2 daemon, the world: MuJoCo simulation and meshcat view) and a real
kernel running lesson 7's cells (start(7), world, `%ros2 run parameter_tests param_vel`,
`%ros2 param set ... velocity 0.2`, the drive), plus one websocket client per learner on the
3D view through JupyterLab's proxy (the learner's browser tab). For N = 1, 2, 4, 8, ... all N
learners drive at once; over a common window each kernel measures its simulation's real-time
factor (the /odom stamps against wall time) and times evenly spread `%ros2 param get` magics.
The bench adds learners until a goal fails (or --max), then stops everything it started.
--record writes the figures to deploy/capacity.yaml (the Kubernetes requests come from there).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import math
import os
import platform
import signal
import statistics
import threading
import time
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

import psutil

from bench._labs import Lab, LabKernel, start_lab, tree_pids
from course_lib.processes import NAME_ENV, process_environ

RTF_GOAL = 0.95
GOALS = ("real-time factor", "param get median", "param get p99")
OTHERS_LIMIT = 0.25  # cores used outside the bench that make a failed round suspect
ATTEMPTS = 3
GET_GOAL_MS = 20.0
REPO = Path(__file__).resolve().parents[1]
RECORD = REPO / "deploy" / "capacity.yaml"

# Lesson 7's cells (notebooks/07_move_the_robot.ipynb), up to the drive.
SETUP = [
    "from course_lib.lessons import start\n\nlesson = start(7)",
    "world = lesson.world()",
    "%ros2 run parameter_tests param_vel",
    "print('viewer port', world.viewer.port)",
]
DRIVE = """\
%ros2 param set /param_vel_node velocity 0.2
lesson.drive_for(3.0)
from bench._capacity_kernel import drive_window
print('window', drive_window(lesson, {t0!r}, {t1!r}, {gets}))
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

    def stop(self) -> None:
        try:
            self.kernel.shutdown()
        finally:
            self.lab.stop()


@dataclass
class Figures:
    """What one learner measured over the window."""

    rtf: float
    gets_ms: list[float]
    top_speed: float
    late_s: float
    cpu_cores: float = 0.0
    pss_mib: float = 0.0
    shm_mib: float = 0.0
    views_per_s: float = 0.0
    by_process: dict[str, tuple[float, float]] = field(default_factory=dict)  # cores, MiB


@dataclass
class Round:
    """One N: every learner's figures and the host's."""

    learners: list[Figures]
    window_s: float
    host_busy_cores: float
    others_cores: float
    load: tuple[float, float, float]
    mem_used_mib: float
    failures: list[str] = field(default_factory=list)

    @property
    def n(self) -> int:
        return len(self.learners)

    @property
    def rtf_min(self) -> float:
        return min(f.rtf for f in self.learners)

    @property
    def gets_ms(self) -> list[float]:
        return [g for f in self.learners for g in f.gets_ms]

    @property
    def pss_mib(self) -> float:
        return statistics.mean(f.pss_mib for f in self.learners)

    @property
    def cpu_cores(self) -> float:
        return statistics.mean(f.cpu_cores for f in self.learners)


def percentile(values: list[float], share: float) -> float:
    """Return the `share` (0..1) percentile of `values`, nearest rank (pure)."""
    ordered = sorted(values)
    if not ordered:
        return math.nan
    return ordered[max(0, math.ceil(share * len(ordered)) - 1)]


def judge(figures: list[Figures]) -> list[str]:
    """Return the goals these figures fail, one sentence each (pure)."""
    failures = []
    worst = min(figures, key=lambda f: f.rtf)
    if not worst.rtf >= RTF_GOAL:
        failures.append(f"real-time factor {worst.rtf:.3f} < {RTF_GOAL} for a learner")
    gets = [g for f in figures for g in f.gets_ms]
    median, p99 = statistics.median(gets), percentile(gets, 0.99)
    if not median < GET_GOAL_MS:
        failures.append(f"param get median {median:.1f} ms >= {GET_GOAL_MS:g} ms")
    if not p99 < GET_GOAL_MS:
        failures.append(f"param get p99 {p99:.1f} ms >= {GET_GOAL_MS:g} ms")
    if any(f.top_speed < 0.15 for f in figures):
        failures.append("a robot did not reach its drive speed")
    return failures


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
    if "-m course_lib lab" in command:
        return "lab (machine service)"
    if "ipykernel_launcher" in command:
        return "kernel"
    name = process_environ(pid).get(NAME_ENV)
    if name:
        return name
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

    def watch(self, learner: Learner) -> None:
        future = asyncio.run_coroutine_threadsafe(self._count(learner), self.loop)
        self.tasks.append(future)

    async def _count(self, learner: Learner) -> None:
        import tornado.websocket

        lab = learner.lab
        url = f"ws://127.0.0.1:{lab.port}/proxy/{learner.viewer_port}/?token={lab.token}"
        connection = await tornado.websocket.websocket_connect(url)
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
def add_learner(number: int, views: Views) -> Learner:
    """Start a lab and a kernel, run lesson 7's first cells; return the learner."""
    lab = start_lab()
    try:
        kernel = LabKernel(lab)
    except BaseException:
        lab.stop()
        raise
    learner = Learner(number, lab, kernel)
    try:
        for cell in SETUP:
            printed = kernel.collect(kernel.submit(cell), timeout=120.0)
        learner.viewer_port = int(printed.split()[-1])
        views.watch(learner)
    except BaseException:
        learner.stop()
        raise
    return learner


def drive_round(learners: list[Learner], window_s: float, gets: int) -> Round:
    """Let every learner drive at once; measure the common window; return the figures."""
    lead = 15.0 + 2.0 * len(learners)  # param set + drive_for(3.0) everywhere before t0
    t0 = time.time() + lead
    t1 = t0 + window_s
    code = DRIVE.format(t0=t0, t1=t1, gets=gets)
    ids = [learner.kernel.submit(code) for learner in learners]
    time.sleep(max(0.0, t0 - time.time()))
    own = os.getpid()
    roots = {learner.number: tree_pids(learner.roots) for learner in learners}
    before = {n: _cpu_seconds(pids) for n, pids in roots.items()}
    labels = {pid: _label(pid) for pids in roots.values() for pid in pids}
    bench_before, busy_before = _cpu_seconds([own])[own], _busy_seconds()
    views_before = {learner.number: learner.view_updates for learner in learners}
    started = time.monotonic()
    time.sleep(window_s / 2)
    pss = {n: _pss_mib(pids) for n, pids in roots.items()}
    shm = {n: shm_mib(pids) for n, pids in roots.items()}
    mem_used = (psutil.virtual_memory().total - psutil.virtual_memory().available) / 2**20
    time.sleep(max(0.0, t1 - time.time()))
    elapsed = time.monotonic() - started
    after = {n: _cpu_seconds(pids) for n, pids in roots.items()}
    bench_cpu = _cpu_seconds([own])[own] - bench_before
    busy = (_busy_seconds() - busy_before) / elapsed
    load = os.getloadavg()
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
        by_process: dict[str, tuple[float, float]] = {}
        for pid in roots[n]:
            label = labels.get(pid, "gone")
            cores, mib = by_process.get(label, (0.0, 0.0))
            by_process[label] = (cores + used.get(pid, 0.0) / elapsed, mib + pss[n].get(pid, 0))
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
    others = busy - (learners_cpu + bench_cpu) / elapsed
    result = Round(figures, elapsed, busy, others, load, mem_used)
    result.failures = judge(figures)
    return result


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


# --- printing ------------------------------------------------------------------------------
def print_round(result: Round) -> None:
    print(f"\nN = {result.n} learners driving at once ({result.window_s:.0f} s window)")
    for number, f in enumerate(result.learners, 1):
        late = f", started {f.late_s:.1f} s late" if f.late_s > 0.5 else ""
        print(
            f"  learner {number:2d}: real-time factor {f.rtf:5.3f}, param get median "
            f"{statistics.median(f.gets_ms):5.1f} ms p99 {percentile(f.gets_ms, 0.99):6.1f} ms "
            f"(n={len(f.gets_ms)}), top speed {f.top_speed:.2f} m/s, CPU {f.cpu_cores:4.2f} "
            f"cores, PSS {f.pss_mib:4.0f} MiB, /dev/shm {f.shm_mib:4.1f} MiB, "
            f"3D view {f.views_per_s:4.1f} updates/s{late}"
        )
    gets = result.gets_ms
    print(
        f"  all: real-time factor min {result.rtf_min:.3f} (goal >= {RTF_GOAL}), param get "
        f"median {statistics.median(gets):.1f} ms p99 {percentile(gets, 0.99):.1f} ms "
        f"(goal < {GET_GOAL_MS:g} ms, n={len(gets)}), {result.pss_mib:.0f} MiB PSS and "
        f"{result.cpu_cores:.2f} cores per learner"
    )
    print(
        f"  host: {result.host_busy_cores:.2f} of {os.cpu_count()} cores busy "
        f"({result.others_cores:.2f} by processes outside the bench), load average "
        f"{result.load[0]:.2f} {result.load[1]:.2f} {result.load[2]:.2f}, "
        f"{result.mem_used_mib / 1024:.1f} GiB in use"
    )
    print(f"  goals: {'; '.join(result.failures) if result.failures else 'all met'}")


def print_processes(result: Round) -> None:
    """Print where one learner's CPU and memory go (the mean over the round's learners)."""
    totals: dict[str, list[float]] = {}
    for f in result.learners:
        for label, (cores, mib) in f.by_process.items():
            entry = totals.setdefault(label, [0.0, 0.0])
            entry[0] += cores / result.n
            entry[1] += mib / result.n
    print(f"  one learner's processes at N = {result.n} (mean):")
    for label, (cores, mib) in sorted(totals.items(), key=lambda kv: -kv[1][0]):
        print(f"    {cores:5.2f} cores {mib:6.0f} MiB  {label}")


def requests(cpu_cores: float, memory_mib: float) -> dict[str, dict[str, object]]:
    """Return a learner's Kubernetes requests and limits from the measured figures (pure).

    Guarantees: the measured CPU rounded up to 0.05 cores, the measured memory rounded up to
    64 MiB. Limits: 2 cores (start-up and workspace builds burst; the drive needs the
    guarantee only) and twice the memory guarantee, at least 2 GiB (more kernels open,
    `colcon build`).
    """
    cpu = math.ceil(cpu_cores * 20 - 1e-9) / 20
    memory = math.ceil(memory_mib / 64) * 64
    return {
        "guarantee": {"cpu": cpu, "memory": f"{memory}M"},
        "limit": {"cpu": 2.0, "memory": f"{max(2 * memory, 2048)}M"},
    }


def summary(rounds: list[Round]) -> dict[str, object]:
    """Return the figures of the whole run, as deploy/capacity.yaml records them (pure)."""
    passed = [r for r in rounds if not r.failures]
    failed = next((r for r in rounds if r.failures), None)
    realtime = [r for r in rounds if r.rtf_min >= RTF_GOAL]  # every simulation kept up
    basis = passed[-1] if passed else (realtime[-1] if realtime else rounds[0])
    alone = rounds[0]
    cores = os.cpu_count() or 1
    memory_gib = psutil.virtual_memory().total / 2**30

    def first(goal: str) -> int | None:
        return next((r.n for r in rounds if any(f.startswith(goal) for f in r.failures)), None)

    return {
        "first_failing": {goal: first(goal) for goal in GOALS},
        "held": passed[-1].n if passed else 0,
        "held_realtime": realtime[-1].n if realtime else 0,
        "first_failing_n": failed.n if failed else None,
        "why": "; ".join(failed.failures) if failed else "",
        "basis_n": basis.n,
        "cpu_cores_alone": round(alone.cpu_cores, 3),
        "memory_mib_alone": round(alone.pss_mib),
        "cpu_cores_per_learner": round(basis.cpu_cores, 3),
        "memory_mib_per_learner": round(basis.pss_mib),
        "learners_per_core_measured": round((passed[-1].n if passed else 0) / cores, 2),
        "learners_per_core_realtime": round((realtime[-1].n if realtime else 0) / cores, 2),
        "learners_per_core_cpu": round(1 / basis.cpu_cores, 2) if basis.cpu_cores else None,
        "learners_per_gib": round(1024 / basis.pss_mib, 2),
        "host": f"{cores} cores ({platform.processor() or platform.machine()}), "
        f"{memory_gib:.1f} GiB",
        "rounds": [
            {
                "n": r.n,
                "rtf_min": round(r.rtf_min, 3),
                "get_median_ms": round(statistics.median(r.gets_ms), 1),
                "get_p99_ms": round(percentile(r.gets_ms, 0.99), 1),
                "mib_per_learner": round(r.pss_mib),
                "cpu_cores_per_learner": round(r.cpu_cores, 3),
                "load_average": [round(x, 2) for x in r.load],
                "others_cores": round(r.others_cores, 2),
                "goals": "; ".join(r.failures) or "all met",
            }
            for r in rounds
        ],
    }


def print_class(facts: dict[str, object], load_before: tuple[float, ...], took: float) -> None:
    print("\nWhat it means for a class (this host)")
    print(
        f"  held {facts['held']} learners with every goal met; first failing N: "
        f"{facts['first_failing_n'] or 'none up to the cap'}"
        + (f" ({facts['why']})" if facts["why"] else "")
    )
    firsts = facts["first_failing"]
    assert isinstance(firsts, dict)
    print(
        "  first failing N by goal: "
        + ", ".join(f"{goal} {n or 'none'}" for goal, n in firsts.items())
    )
    print(
        f"  per learner at N = {facts['basis_n']}: {facts['cpu_cores_per_learner']} cores, "
        f"{facts['memory_mib_per_learner']} MiB PSS (alone: {facts['cpu_cores_alone']} cores, "
        f"{facts['memory_mib_alone']} MiB, what one pod of its own needs)"
    )
    print(
        f"  learners per core: {facts['learners_per_core_measured']} measured (all goals met), "
        f"{facts['learners_per_core_realtime']} with every simulation at real time "
        f"(N = {facts['held_realtime']}), {facts['learners_per_core_cpu']} by CPU share alone; "
        "learners per GiB: "
        f"{facts['learners_per_gib']}"
    )
    print(
        f"  load average before the bench: {load_before[0]:.2f} {load_before[1]:.2f} "
        f"{load_before[2]:.2f}; bench took {took:.0f} s"
    )


def record(facts: dict[str, object], load_before: tuple[float, ...]) -> None:
    """Write deploy/capacity.yaml from this run's figures."""
    import yaml

    cpu = max(float(facts["cpu_cores_alone"]), float(facts["cpu_cores_per_learner"]))  # type: ignore[arg-type]
    data = {
        "measured": {
            "date": f"{datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC",
            "host": facts["host"],
            "by": "python -m bench.class_capacity --record",
            "load_average_before": [round(x, 2) for x in load_before],
            "learners_held": facts["held"],
            "first_failing_n": facts["first_failing_n"],
            "why": facts["why"],
            "first_failing_n_by_goal": facts["first_failing"],
            "rounds": facts["rounds"],
        },
        "per_learner": {
            "cpu_cores": cpu,
            "memory_mib_alone": facts["memory_mib_alone"],
            "memory_mib_shared": facts["memory_mib_per_learner"],
        },
        "class": {
            "learners_per_core": facts["learners_per_core_measured"],
            "learners_per_core_realtime": facts["learners_per_core_realtime"],
            "learners_per_gib": facts["learners_per_gib"],
        },
        "kubernetes": requests(cpu, float(facts["memory_mib_alone"])),  # type: ignore[arg-type]
    }
    RECORD.parent.mkdir(exist_ok=True)
    RECORD.write_text(
        "# Written by `python -m bench.class_capacity --record`: what one learner costs.\n"
        "# per_learner.cpu_cores: the larger of alone and at the N the figures come from\n"
        "# (the largest N that met every goal, else the largest with every simulation at\n"
        "# real time);\n"
        "# memory_mib_alone: PSS of one learner's processes with no other learner (one pod);\n"
        "# memory_mib_shared: PSS per learner at that N (libraries shared across learners).\n"
        "# kubernetes: what deploy/kubernetes/values.yaml must request (bench.class_capacity\n"
        "# .requests; tests/unit/deploy/test_kubernetes_files.py checks they agree).\n"
        + yaml.safe_dump(data, sort_keys=False)
    )
    print(f"\nwrote {RECORD.relative_to(REPO)}")


def sizes(cap: int) -> list[int]:
    """Return 1, 2, 4, ... up to `cap` (pure)."""
    out, n = [], 1
    while n <= cap:
        out.append(n)
        n *= 2
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max", type=int, default=16, help="most learners (default 16)")
    parser.add_argument("--window", type=float, default=30.0, help="seconds measured per N")
    parser.add_argument("--gets", type=int, default=200, help="param gets per learner per N")
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
    signal.signal(signal.SIGTERM, signal.default_int_handler)  # stop everything on SIGTERM too
    started = time.monotonic()
    load_before = os.getloadavg()
    print(
        f"{os.cpu_count()} cores, {psutil.virtual_memory().total / 2**30:.1f} GiB; load average "
        f"{load_before[0]:.2f} {load_before[1]:.2f} {load_before[2]:.2f} before the bench",
        flush=True,
    )
    learners: list[Learner] = []
    rounds: list[Round] = []
    views = Views()
    try:
        for n in sizes(args.max):
            while len(learners) < n:
                learners.append(add_learner(len(learners) + 1, views))
            attempts: list[Round] = []
            for attempt in range(1, ATTEMPTS + 1):
                attempts.append(drive_round(learners, args.window, args.gets))
                print_round(attempts[-1])
                if not attempts[-1].failures or attempts[-1].others_cores <= args.others:
                    break
                if attempt < ATTEMPTS:
                    print(f"  others used {attempts[-1].others_cores:.2f} cores: measured again")
                    wait_for_quiet(args.others)
            rounds.append(min(attempts, key=lambda r: (len(r.failures), r.others_cores)))
            if len(attempts) > 1:
                print(f"  N = {n}: kept the attempt with others at {rounds[-1].others_cores:.2f}")
            if len(rounds) == 1:
                print_processes(rounds[0])
            if rounds[-1].failures and not (args.keep_going and rounds[-1].rtf_min >= RTF_GOAL):
                break
    finally:
        views.stop()
        for learner in reversed(learners):
            learner.stop()
    if not rounds:
        raise SystemExit("no round finished")
    facts = summary(rounds)
    print_class(facts, load_before, time.monotonic() - started)
    if args.record:
        record(facts, load_before)


if __name__ == "__main__":
    main()
