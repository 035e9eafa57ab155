"""Measure the `ros2` doors: notebook magic and terminal command round trips, node discovery.

Run: .venv/bin/python bench/ros2_latency.py [--runs N]
Prints medians (and max) in milliseconds; the real Jazzy tools take 1.4-2.0 s per `param get`.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from course_lib.core.waiting import wait_until  # noqa: E402
from course_lib.notebook.magics import run_line  # noqa: E402
from course_lib.ros2 import client, start_daemon  # noqa: E402
from course_lib.ros2.node.connect import daemon_socket  # noqa: E402
from course_lib.session.session import get_session  # noqa: E402

NODE = REPO / "tests" / "golden" / "ros2" / "nodes" / "param_vel_node.py"


def _timed(action, runs: int) -> list[float]:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        action()
        times.append(time.perf_counter() - start)
    return times


# The real Jazzy tools on this stack (tests/golden/ros2: medians over 10 runs, daemon warm or
# --no-daemon); `param set` without daemon is the median wall time of the golden set cases.
GOLDEN = REPO / "tests" / "golden" / "ros2" / "cases.json"
REAL_GET = "real: 2.0 s no daemon, 1.4 s daemon"


def _real_set() -> str:
    cases = json.loads(GOLDEN.read_text())
    walls = [c["wall_s"] for c in cases if c["command"].startswith("ros2 param set")]
    return f"real: {statistics.median(walls):.1f} s no daemon (n={len(walls)} golden runs)"


def _report(label: str, times: list[float], real: str = "") -> None:
    print(
        f"{label:40s} median {statistics.median(times) * 1e3:7.1f} ms  "
        f"max {max(times) * 1e3:7.1f} ms  (n={len(times)}) {real}".rstrip()
    )


def _terminal(env: dict[str, str], *args: str) -> None:
    proc = subprocess.run(
        [str(REPO / ".venv" / "bin" / "ros2"), *args],
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr


# The real tools for the part-2 verbs (tests/golden/ros2/cases_part2.json wall times).
PART2 = {
    "service list": (("service", "list"), "daemon_service_list_t"),
    "topic info /cmd_vel": (("topic", "info", "/cmd_vel"), "daemon_topic_info_unknown"),
    "interface show": (
        ("interface", "show", "rcl_interfaces/msg/ParameterDescriptor"),
        "interface_show_parameter_descriptor",
    ),
}


def _part2(env: dict[str, str], runs: int) -> None:
    """Terminal medians of the service/topic/interface verbs (target: under 0.1 s)."""
    walls = {
        c["case"]: c["wall_s"]
        for c in json.loads((GOLDEN.parent / "cases_part2.json").read_text())
    }
    python = [str(REPO / ".venv" / "bin" / "python"), "-c", "pass"]
    _report(
        "terminal python -c pass (floor)",
        _timed(lambda: subprocess.run(python, env=env, check=True), runs),
    )
    from course_lib.ros2.command.commands import run_collected

    _report(
        "in-process ros2 interface show (no start)",
        _timed(lambda: run_collected(list(PART2["interface show"][0])), runs),
    )
    for label, (argv, case) in PART2.items():
        _terminal(env, *argv)  # warm the daemon
        _report(
            f"terminal ros2 {label}",
            _timed(lambda argv=argv: _terminal(env, *argv), runs),
            f"real: {walls[case]:.2f} s ({case})",
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--runs", type=int, default=30)
    runs = parser.parse_args().runs
    session = get_session()
    env = {**session.env, "PYTHONPATH": str(REPO)}
    daemon = start_daemon(session.env)
    node = session.spawn([sys.executable, str(NODE)], name="vel")
    try:
        assert client().wait_for_node("/param_vel_node", include_hidden=False, timeout=10)
        assert wait_until(lambda: daemon_socket(session.domain_id).exists(), 15)
        print(f"domain {session.domain_id}")
        _report(
            "magic  %ros2 param get",
            _timed(lambda: run_line("param get /param_vel_node velocity"), runs),
            REAL_GET,
        )
        _report(
            "magic  %ros2 param set",
            _timed(lambda: run_line("param set /param_vel_node velocity 0.0"), runs),
            _real_set(),
        )
        _terminal(env, "param", "get", "/param_vel_node", "velocity")  # warm the daemon
        _report(
            "terminal ros2 param get (daemon warm)",
            _timed(
                lambda: _terminal(env, "param", "get", "/param_vel_node", "velocity"), runs // 2
            ),
            REAL_GET,
        )
        _report(
            "terminal ros2 param set (daemon warm)",
            _timed(
                lambda: _terminal(env, "param", "set", "/param_vel_node", "velocity", "0.0"),
                runs // 2,
            ),
            _real_set(),
        )
        _part2(env, runs // 2)
        node.stop()
        spawn_to_answer = []
        for _ in range(max(3, runs // 6)):
            start = time.perf_counter()
            child = session.spawn([sys.executable, str(NODE)], name="vel")
            out = run_line("param get /param_vel_node velocity").output
            spawn_to_answer.append(time.perf_counter() - start)
            assert out.stdout == "Double value is: 0.0\n", out
            child.stop()
            wait_until(
                lambda: "/param_vel_node" not in [n.full_name for n in client().node_names()], 10
            )
        _report("node spawn -> first answered param get", spawn_to_answer)
        _report(
            "missing node -> 'Node not found'",
            _timed(lambda: run_line("param get /no_such_node velocity"), 2),
        )
    finally:
        node.stop()
        daemon.stop()
        session.close()


if __name__ == "__main__":
    main()
