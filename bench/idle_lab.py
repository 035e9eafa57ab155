"""What an idle lab costs: one lab with the world running, the robot still, nobody watching.

Run: .venv/bin/python -m bench.idle_lab [--seconds 60] [--settle 20] [--runs 1]
     [--velocity 0.0] [--json]
An idle lab is what a learner leaves behind after lesson 7's first cells (start(7), the world,
`%ros2 run parameter_tests param_vel`) with the velocity at 0, no 3D view open in a browser and
no cell running. The bench starts one such lab (as `make lab` does) and one real kernel, waits
`--settle` seconds, then measures each of the lab's and kernel's processes' CPU (user + system,
in cores) over `--seconds`, and prints one table per run: every process, the total, and the
total beside `param_vel` (the tutorial's node ticks 10 times a second by design; issue 66's goal
is that the rest costs at most 0.005 cores). With `--runs` > 1 the same lab is measured again
and the median of each row is printed last. `--velocity 0.2` measures a driving learner instead;
`--json` prints the last window's totals (cores, PSS in MiB) as one JSON line (bench.image
compares a lab in the course's image with a native one this way).
"""

from __future__ import annotations

import argparse
import json
import signal
import statistics
import time

from bench._labs import LabKernel, start_lab, tree_pids
from bench.class_capacity import _cpu_seconds, _label, _pss_mib

GOAL_CORES = 0.005  # issue 66: an idle lab beside the tutorial's own node
TUTORIAL_NODE = "param_vel"

# Lesson 7's first cells (notebooks/07_move_the_robot.ipynb), the robot left still.
SETUP = [
    "from course_lib.lessons import start\n\nlesson = start(7)",
    "world = lesson.world()",
    "%ros2 run parameter_tests param_vel",
]
VELOCITY_CELL = "%ros2 param set /param_vel_node velocity {velocity}"


def measure(roots: list[int], seconds: float) -> dict[str, float]:
    """Return the cores each process (by label) of `roots`' trees used over `seconds`."""
    pids = tree_pids(roots)
    labels = {pid: _label(pid) for pid in pids}
    before, started = _cpu_seconds(pids), time.monotonic()
    time.sleep(seconds)
    after, elapsed = _cpu_seconds(pids), time.monotonic() - started
    cores: dict[str, float] = {}
    for pid, used in after.items():
        if pid in before:
            label = labels[pid]
            cores[label] = cores.get(label, 0.0) + (used - before[pid]) / elapsed
    return cores


def is_tutorial(label: str) -> bool:
    """Say whether a process label is the tutorial's own node (pure)."""
    return TUTORIAL_NODE in label


def table(title: str, cores: dict[str, float]) -> str:
    """Return one run's (or the medians') per-process table with its totals (pure)."""
    width = max([len(label) for label in cores] + [24])
    lines = [title, f"  {'process':<{width}}  cores"]
    for label, used in sorted(cores.items(), key=lambda item: -item[1]):
        lines.append(f"  {label:<{width}}  {used:.4f}")
    total = sum(cores.values())
    beside = sum(used for label, used in cores.items() if not is_tutorial(label))
    lines.append(f"  {'total':<{width}}  {total:.4f}")
    lines.append(
        f"  {'total without ' + TUTORIAL_NODE:<{width}}  {beside:.4f}"
        f"   (goal <= {GOAL_CORES:g}: {'met' if beside <= GOAL_CORES else 'not met'})"
    )
    return "\n".join(lines)


def medians(runs: list[dict[str, float]]) -> dict[str, float]:
    """Return the median of each process's cores over `runs` (absent counts 0) (pure)."""
    labels = {label for run in runs for label in run}
    return {label: statistics.median(run.get(label, 0.0) for run in runs) for label in labels}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="window measured (60)")
    parser.add_argument("--settle", type=float, default=20.0, help="wait before measuring (20)")
    parser.add_argument("--runs", type=int, default=1, help="windows measured on one lab (1)")
    parser.add_argument("--velocity", type=float, default=0.0, help="the robot's (0.0: still)")
    parser.add_argument("--json", action="store_true", help="print the totals as JSON only")
    args = parser.parse_args()
    signal.signal(signal.SIGTERM, signal.default_int_handler)  # stop everything on SIGTERM too
    lab = start_lab()
    kernel = None
    try:
        kernel = LabKernel(lab)
        for cell in [*SETUP, VELOCITY_CELL.format(velocity=args.velocity)]:
            kernel.run(cell)
        time.sleep(args.settle)
        runs = []
        for number in range(1, args.runs + 1):
            runs.append(measure([lab.pid, kernel.pid], args.seconds))
            if not args.json:
                print(table(f"run {number}, {args.seconds:g} s:", runs[-1]), flush=True)
        if args.json:
            pss = sum(_pss_mib(tree_pids([lab.pid, kernel.pid])).values())
            print(json.dumps({"cores": sum(runs[-1].values()), "pss_mib": pss}), flush=True)
        elif len(runs) > 1:
            print(table(f"medians of {len(runs)} runs:", medians(runs)), flush=True)
    finally:
        if kernel is not None:
            kernel.shutdown()
        lab.stop()


if __name__ == "__main__":
    main()
