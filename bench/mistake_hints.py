"""Measure what a notebook hint adds to a failing `%ros2` command (and to a params-file run).

Run: .venv/bin/python bench/mistake_hints.py [--runs N]
For each common mistake: the command's median wall time (hints off) and what looking up its
hint adds (median, measured alone: the difference of two noisy wall times would hide it);
then the params-file check alone (what `%ros2 run`/`lesson.run`/`lesson.launch`
add after the node's first line). A right command asks nothing more (no hint is looked for).
"""

from __future__ import annotations

import argparse
import shlex
import statistics
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from course_lib.notebook import hints  # noqa: E402
from course_lib.notebook.magics import run_line  # noqa: E402
from course_lib.ros2 import client  # noqa: E402
from course_lib.session.session import get_session  # noqa: E402

NODES = REPO / "tests" / "golden" / "ros2" / "nodes"
MISTAKES = [
    "param set /param_vel_node velocity 1",
    "param set /param_vel_node velocity abc",
    "param set /param_vel_node velocty 0.2",
    "param get /param_vel_node velocty",
    "param describe /param_vel_node velocty",
    "param set /param_types_node gains [1.0, 2.0]",
    "param get /param_vel velocity",
    "param set /param_vel_node velocity 0.2",  # a right one: no hint looked for
]


def _median_ms(action, runs: int) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        action()
        times.append(time.perf_counter() - start)
    return statistics.median(times) * 1e3


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--runs", type=int, default=10)
    runs = parser.parse_args().runs
    session = get_session()
    for script, node in (("param_vel_node.py", "vel"), ("param_types_node.py", "types")):
        session.spawn([sys.executable, str(NODES / script)], name=node)
    for node in ("/param_vel_node", "/param_types_node"):
        assert client().wait_for_node(node, include_hidden=False, timeout=15)
        assert client().services_ready(node, timeout=15)
    print(f"{'command':48s} {'command':>9s} {'its hint':>9s}")
    for command in MISTAKES:
        hints.set_enabled(False)
        whole = _median_ms(lambda c=command: run_line(c), runs)
        hints.set_enabled(True)
        output = run_line(command).output
        argv = shlex.split(command)
        hint = _median_ms(
            lambda a=argv, o=output: hints.command_hint(a, o.stdout, o.stderr, client), runs
        )
        print(f"{command:48s} {whole:7.1f}ms {hint:+7.1f}ms")
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "other.yaml"
        path.write_text("/some_other_node:\n  ros__parameters:\n    velocity: 0.9\n")
        check = _median_ms(
            lambda: hints.params_file_hints([str(path)], ["/param_vel_node"], client), runs
        )
    print(f"{'params-file check after a run or launch':48s} {'':9s} {check:+7.1f}ms")
    session.close()


if __name__ == "__main__":
    main()
