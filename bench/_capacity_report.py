"""The class bench's figures: one round's numbers, the goals, what they mean for a class.

Pure except for printing and `record()` (which writes deploy/capacity.yaml); used by
bench/class_capacity.py, and by tests/unit/repo/deploy for the Kubernetes requests rule.
"""

from __future__ import annotations

import math
import os
import platform
import statistics
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import psutil

RTF_GOAL = 0.95
GET_GOAL_MS = 20.0
MEMORY_GOAL_MIB = 200.0  # PSS per learner; reported beside the goals, never stops the run
IDLE_GOAL_CORES = 0.005  # an idle learner beside the tutorial's own node (bench.idle_lab)
BENCH_LATE_S = 1.0  # a window the bench began later than this measured the bench's own stall
TUTORIAL_NODE = "param_vel"  # ticks ten times a second by design: not an idle lab's own cost
GOALS = ("real-time factor", "param get median", "param get p99")
REPO = Path(__file__).resolve().parents[1]
RECORD = REPO / "deploy" / "capacity.yaml"


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
class Usage:
    """What one learner's processes used over the window: cores and PSS, by process."""

    by_process: dict[str, tuple[float, float]] = field(default_factory=dict)  # cores, MiB

    @property
    def cpu_cores(self) -> float:
        return sum(cores for cores, _ in self.by_process.values())

    @property
    def pss_mib(self) -> float:
        return sum(mib for _, mib in self.by_process.values())

    @property
    def beside_tutorial(self) -> float:
        """Return the cores of every process but the tutorial's own node."""
        return sum(c for label, (c, _) in self.by_process.items() if TUTORIAL_NODE not in label)


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
    idle: list[Usage] = field(default_factory=list)  # the idle learners beside the drivers
    hub: Usage | None = None  # the class hub's own processes (bench.hub_class)
    bench_late_s: float = 0.0  # how late the bench itself began the window (starved)

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


def measure_again(result: Round, others_limit: float) -> str | None:
    """Say why a round's failures may not be the class's own (None: they are): processes
    outside the bench used the CPU, or the bench itself, starved, began its window late
    (its clients of the 3D views and kernels then fell behind too) (pure)."""
    if not result.failures:
        return None
    if result.bench_late_s > BENCH_LATE_S:
        return f"the bench began its window {result.bench_late_s:.1f} s late"
    if result.others_cores > others_limit:
        return f"others used {result.others_cores:.2f} cores"
    return None


def kept_attempt(result: Round) -> tuple[int, bool, float]:
    """Order the attempts at one N: fewest failures, then a window the bench began on time,
    then the least CPU used outside the bench (pure)."""
    return (len(result.failures), result.bench_late_s > BENCH_LATE_S, result.others_cores)


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
    if result.bench_late_s > BENCH_LATE_S:
        print(
            f"  the bench began this window {result.bench_late_s:.1f} s late (its own process "
            "starved): the figures are its stall as much as the class's"
        )
    memory = "met" if result.pss_mib <= MEMORY_GOAL_MIB else "fails"
    print(
        f"  memory: {result.pss_mib:.0f} MiB PSS per learner (goal <= {MEMORY_GOAL_MIB:g} MiB): "
        f"{memory}"
    )


def mean_processes(
    tables: list[dict[str, tuple[float, float]]],
) -> dict[str, tuple[float, float]]:
    """Return the mean cores and MiB of each process label over learners' tables (pure)."""
    totals: dict[str, list[float]] = {}
    for table in tables:
        for label, (cores, mib) in table.items():
            entry = totals.setdefault(label, [0.0, 0.0])
            entry[0] += cores / len(tables)
            entry[1] += mib / len(tables)
    return {label: (cores, mib) for label, (cores, mib) in totals.items()}


def _print_table(title: str, table: dict[str, tuple[float, float]], digits: int) -> None:
    print(title)
    for label, (cores, mib) in sorted(table.items(), key=lambda kv: -kv[1][0]):
        print(f"    {cores:{digits + 3}.{digits}f} cores {mib:6.0f} MiB  {label}")
    print(
        f"    {sum(c for c, _ in table.values()):{digits + 3}.{digits}f} cores "
        f"{sum(m for _, m in table.values()):6.0f} MiB  all"
    )


def print_processes(result: Round) -> None:
    """Print where one learner's CPU and memory go (the mean over the round's learners), the
    idle learners' apart."""
    driving = mean_processes([f.by_process for f in result.learners])
    _print_table(f"  one driving learner's processes at N = {result.n} (mean):", driving, 2)
    if result.idle:
        idle = mean_processes([u.by_process for u in result.idle])
        _print_table(f"  one idle learner's processes ({len(result.idle)} idle, mean):", idle, 4)
        beside = sum(c for label, (c, _) in idle.items() if TUTORIAL_NODE not in label)
        verdict = "met" if beside <= IDLE_GOAL_CORES else "not met"
        print(
            f"    {beside:7.4f} cores beside {TUTORIAL_NODE} "
            f"(goal <= {IDLE_GOAL_CORES:g}: {verdict})"
        )
    if result.hub is not None:
        _print_table(f"  the hub's own processes at N = {result.n}:", result.hub.by_process, 3)
        share = result.hub.cpu_cores / result.n
        print(f"    {share:.4f} cores and {result.hub.pss_mib / result.n:.1f} MiB per learner")


def first_failing(facts: dict[str, object]) -> str:
    """Return which goal fails first as learners are added, as one sentence (pure)."""
    firsts = dict(facts["first_failing"])  # type: ignore[call-overload]
    rounds = facts["rounds"]
    assert isinstance(rounds, list)
    failing = {goal: n for goal, n in firsts.items() if n is not None}
    if not failing:
        return f"none up to N = {rounds[-1]['n']}"
    n = min(failing.values())
    goals = " and ".join(goal for goal, at in failing.items() if at == n)
    return f"{goals} at N = {n}"


def memory_summary(rounds: list[dict[str, object]]) -> str:
    """Say from which N on the memory goal holds, as one sentence (pure).

    Unlike the other goals, memory per learner falls as learners are added: the libraries
    every learner maps are counted once per host and shared out among them (PSS).
    """
    sizes = ", ".join(f"{r['mib_per_learner']} MiB at N = {r['n']}" for r in rounds)
    within = [float(r["mib_per_learner"]) <= MEMORY_GOAL_MIB for r in rounds]  # type: ignore[arg-type]
    start = len(within)
    while start > 0 and within[start - 1]:
        start -= 1  # the first round from which every later round is within the goal
    if start == 0:
        return f"within {MEMORY_GOAL_MIB:g} MiB at every N ({sizes})"
    if start < len(within):
        return (
            f"within {MEMORY_GOAL_MIB:g} MiB from N = {rounds[start]['n']} on ({sizes}; "
            "the libraries are counted once per host, so fewer learners each carry more)"
        )
    return f"above {MEMORY_GOAL_MIB:g} MiB at the largest N ({sizes})"


def requests(cpu_cores: float, memory_mib: float) -> dict[str, dict[str, object]]:
    """Return a learner's Kubernetes requests and limits from the measured figures (pure).

    Guarantees: the CPU rounded up to 0.05 cores, the memory rounded up to 64 MiB. Limits: at
    least 2 cores (start-up and workspace builds burst; the drive needs the guarantee only)
    and twice the memory guarantee, at least 2 GiB (more kernels open, `colcon build`).
    `record()` passes the cores per learner that held every goal (see `held_cores`), so
    Kubernetes never packs more learners on a core than the bench saw keep every goal.
    """
    cpu = math.ceil(cpu_cores * 20 - 1e-9) / 20
    memory = math.ceil(memory_mib / 64) * 64
    return {
        "guarantee": {"cpu": cpu, "memory": f"{memory}M"},
        "limit": {"cpu": max(2.0, cpu), "memory": f"{max(2 * memory, 2048)}M"},
    }


def held_cores(measured_cores: float, host_cores: int, held: int) -> float:
    """Return the CPU one learner must be given: what they used, and never less than the
    host's cores over the learners that held every goal (all of them if none did) (pure)."""
    return max(measured_cores, host_cores / held if held else float(host_cores))


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

    idle = rounds[-1].idle

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
        "idle": {
            "learners": len(idle),
            "cpu_cores": round(statistics.mean(u.cpu_cores for u in idle), 4),
            "cpu_cores_beside_tutorial": round(
                statistics.mean(u.beside_tutorial for u in idle), 4
            ),
            "memory_mib": round(statistics.mean(u.pss_mib for u in idle)),
        }
        if idle
        else None,
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
    print(f"  first goal to fail as learners are added: {first_failing(facts)}")
    rounds = facts["rounds"]
    assert isinstance(rounds, list)
    print(f"  memory per learner: {memory_summary(rounds)}")
    idle = facts.get("idle")
    if isinstance(idle, dict):
        beside = float(idle["cpu_cores_beside_tutorial"])
        print(
            f"  an idle learner ({idle['learners']} beside the drivers at N = {rounds[-1]['n']}): "
            f"{idle['cpu_cores']} cores, {beside} beside {TUTORIAL_NODE} (goal <= "
            f"{IDLE_GOAL_CORES:g}: {'met' if beside <= IDLE_GOAL_CORES else 'not met'}), "
            f"{idle['memory_mib']} MiB PSS"
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


def record(facts: dict[str, object], load_before: tuple[float, ...], gets: str) -> None:
    """Write deploy/capacity.yaml from this run's figures (its `hub` section kept)."""
    cpu = max(float(facts["cpu_cores_alone"]), float(facts["cpu_cores_per_learner"]))  # type: ignore[arg-type]
    data: dict[str, Any] = {
        "measured": {
            "date": f"{datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC",
            "host": facts["host"],
            "by": "python -m bench.class_capacity --record",
            "load_average_before": [round(x, 2) for x in load_before],
            "param_gets": gets,
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
    }
    hub = _recorded().get("hub")
    if hub is not None:
        data["hub"] = hub  # bench.hub_class's figures stay until it records again
    _write_record(data)


def _recorded() -> dict[str, Any]:
    """Return deploy/capacity.yaml as it is (empty if there is none)."""
    import yaml

    return dict(yaml.safe_load(RECORD.read_text()) or {}) if RECORD.exists() else {}


def pod_memory_mib(record: dict[str, Any]) -> float:
    """Return the memory one learner's pod needs alone: the larger of a lab's learner and a
    hub's (a pod runs the hub's single-user server, `course_lib hub-lab`) (pure)."""
    lab = float(record["per_learner"]["memory_mib_alone"])
    hub = record.get("hub") or {}
    return max(lab, float(hub.get("learner_memory_mib_alone", 0)))


def _write_record(data: dict[str, Any]) -> None:
    """Write deploy/capacity.yaml: `data` with the Kubernetes requests that follow from it."""
    import yaml

    measured, per = data["measured"], data["per_learner"]
    cores = int(str(measured["host"]).split()[0])
    data["kubernetes"] = requests(
        held_cores(float(per["cpu_cores"]), cores, int(measured["learners_held"])),
        pod_memory_mib(data),
    )
    if "hub" in data:  # last in the file: the class's figures and requests come first
        data["hub"] = data.pop("hub")
    RECORD.parent.mkdir(exist_ok=True)
    RECORD.write_text(
        "# Written by `python -m bench.class_capacity --record`: what one learner costs.\n"
        "# per_learner.cpu_cores: the larger of alone and at the N the figures come from\n"
        "# (the largest N that met every goal, else the largest with every simulation at\n"
        "# real time);\n"
        "# memory_mib_alone: PSS of one learner's processes with no other learner (one pod);\n"
        "# memory_mib_shared: PSS per learner at that N (libraries shared across learners).\n"
        "# kubernetes: what deploy/kubernetes/values.yaml must request (requests() of\n"
        "# held_cores() in bench/_capacity_report.py: never more learners per core than held\n"
        "# every goal; tests/unit/repo/deploy/test_kubernetes_files.py checks), its memory\n"
        "# the larger of memory_mib_alone and hub.learner_memory_mib_alone (pod_memory_mib).\n"
        "# hub: written by `python -m bench.hub_class --record` (a real class hub, root):\n"
        "# a learner through the hub, and the hub's own processes at hub.learners.\n"
        + yaml.safe_dump(data, sort_keys=False)
    )
    print(f"\nwrote {RECORD.relative_to(REPO)}")


def hub_summary(rounds: list[Round], *, walled: bool) -> dict[str, Any]:
    """Return bench.hub_class's figures: a learner through the hub alone (the first round)
    and in the class (the last), and the hub's own processes in the class (pure)."""
    alone, last = rounds[0], rounds[-1]
    own = last.hub or Usage()
    return {
        "date": f"{datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC",
        "by": "python -m bench.hub_class --record",
        "domain_wall": walled,
        "learners": last.n,
        "learner_memory_mib_alone": round(alone.pss_mib),
        "learner_memory_mib_shared": round(last.pss_mib),
        "learner_cpu_cores": round(last.cpu_cores, 3),
        "rtf_min": round(last.rtf_min, 3),
        "get_median_ms": round(statistics.median(last.gets_ms), 1),
        "get_p99_ms": round(percentile(last.gets_ms, 0.99), 1),
        "own": {
            "cpu_cores": round(own.cpu_cores, 3),
            "memory_mib": round(own.pss_mib),
            "cpu_cores_per_learner": round(own.cpu_cores / last.n, 4),
            "memory_mib_per_learner": round(own.pss_mib / last.n, 1),
            "processes": {
                label: {"cpu_cores": round(cores, 3), "memory_mib": round(mib)}
                for label, (cores, mib) in sorted(own.by_process.items())
            },
        },
    }


def record_hub(facts: dict[str, Any]) -> None:
    """Write bench.hub_class's figures into deploy/capacity.yaml (its `hub` section), and the
    Kubernetes requests that follow."""
    data = _recorded()
    if "per_learner" not in data:
        raise SystemExit(f"{RECORD} has no class figures: run bench.class_capacity --record")
    data["hub"] = facts
    _write_record(data)
