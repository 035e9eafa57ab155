"""Measure first calls of `ros2 node list` in a terminal: cold (no daemon), warm, --no-daemon.

Run: .venv/bin/python -m bench.ros2_discovery [--runs N]
The tutorial node runs; each cold call starts from no daemon (stopped with `ros2 daemon
stop`) and must list the node. Goals (issue 15): cold under 1 s and never empty, warm under
0.1 s. The real tools: 0.99 s with --no-daemon (missing the node about half the time), 0.33 s
with a warm daemon.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from course_lib.processes.children import spawn  # noqa: E402
from course_lib.processes.domain import lease_domain  # noqa: E402
from course_lib.session.session import session_env  # noqa: E402

NODE = REPO / "tests" / "golden" / "ros2" / "nodes" / "param_vel_node.py"
ROS2 = str(Path(sys.executable).parent / "ros2")


def _call(env: dict[str, str], *args: str) -> tuple[float, bool]:
    start = time.perf_counter()
    out = subprocess.run([ROS2, *args], env=env, capture_output=True, text=True, check=False)
    return time.perf_counter() - start, out.stdout == "/param_vel_node\n"


def _report(label: str, runs: list[tuple[float, bool]], goal: str) -> None:
    times = [t for t, _ok in runs]
    hits = sum(ok for _t, ok in runs)
    print(
        f"{label:34s} median {statistics.median(times) * 1e3:6.0f} ms  "
        f"max {max(times) * 1e3:6.0f} ms  listed the node {hits}/{len(runs)}  ({goal})"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--runs", type=int, default=20)
    runs = parser.parse_args().runs
    lease = lease_domain({})
    env = {**session_env(lease.domain_id), "PYTHONPATH": str(REPO)}
    node = spawn([sys.executable, str(NODE)], name="vel", env=env)
    try:
        assert node.wait_for_line("Velocity parameter is", 30), node.text()
        print(f"domain {lease.domain_id}, tutorial node running")
        cold = []
        for _ in range(runs):
            subprocess.run([ROS2, "daemon", "stop"], env=env, capture_output=True, check=True)
            cold.append(_call(env, "node", "list"))
        _report("ros2 node list, no daemon (cold)", cold, "goal < 1000 ms, never empty")
        warm = [_call(env, "node", "list") for _ in range(runs)]
        _report("ros2 node list, daemon warm", warm, "goal < 100 ms; real 330 ms")
        direct = [_call(env, "node", "list", "--no-daemon") for _ in range(runs)]
        _report("ros2 node list --no-daemon", direct, "real 990 ms, misses ~1/2")
    finally:
        subprocess.run([ROS2, "daemon", "stop"], env=env, capture_output=True, check=False)
        node.stop()
        lease.release()


if __name__ == "__main__":
    main()
