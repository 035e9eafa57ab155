"""Measure the `ros2` doors: notebook magic and terminal command round trips, node discovery.

Run: .venv/bin/python bench/ros2_latency.py [--runs N] [--terminal-only]
Prints medians (and max) in milliseconds; the real Jazzy tools take 1.4-2.0 s per `param get`.
The terminal part runs the clone's `.venv/bin/ros2` for every verb of the golden transcripts,
beside `python -c pass` in the same run (issue 23's target: every verb within 50 ms on a
quiet machine), and times "Node not found" once the daemon has known the domain a while, as
well as `topic echo` of a missing topic and `topic delay` (issue 67).
BENCH_REPO=<another clone> measures that clone's code and `ros2` (a before/after table).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(os.environ.get("BENCH_REPO") or Path(__file__).resolve().parents[1]).resolve()
sys.path.insert(0, str(REPO))

from course_lib.core.waiting import wait_until  # noqa: E402
from course_lib.notebook.magics import run_line  # noqa: E402
from course_lib.ros2 import client, start_daemon  # noqa: E402
from course_lib.ros2.node.connect import daemon_socket  # noqa: E402
from course_lib.session.session import get_session  # noqa: E402

NODE = REPO / "tests" / "golden" / "ros2" / "nodes" / "param_vel_node.py"
STAMPED = NODE.with_name("stamped_talker.py")  # /stamped, TwistStamped, 10 Hz


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


# The console script pip writes for `ros2` (what the venv's `ros2` was before issue 23): a
# Python that the ROS wheels' bootstrapper re-executes, then the full command.
FULL = "import sys; from course_lib.ros2.command.cli import main; sys.exit(main())"


def _terminal(env: dict[str, str], *args: str, code: int = 0, full: bool = False) -> None:
    bin_dir = REPO / ".venv" / "bin"
    start = [str(bin_dir / "python"), "-c", FULL] if full else [str(bin_dir / "ros2")]
    proc = subprocess.run(
        [*start, *args],
        env=env,
        capture_output=True,
        text=True,
        check=False,
        cwd=str(GOLDEN.parent),
    )
    assert proc.returncode == code, (args, proc.stdout, proc.stderr)


# One command per verb of the golden transcripts (tests/golden/ros2) the daemon can answer
# with the tutorial node running; `run` and `launch` start processes and are left out.
VERBS: list[tuple[str, ...]] = [
    ("node", "list"),
    ("node", "info", "/param_vel_node"),
    ("param", "get", "/param_vel_node", "velocity"),
    ("param", "set", "/param_vel_node", "velocity", "0.0"),
    ("param", "list", "/param_vel_node"),
    ("param", "describe", "/param_vel_node", "velocity"),
    ("param", "dump", "/param_vel_node"),
    ("param", "load", "/param_vel_node", "params/vel_wildcard.yaml"),
    ("topic", "list"),
    ("topic", "info", "/cmd_vel"),
    ("topic", "type", "/cmd_vel"),
    ("topic", "find", "geometry_msgs/msg/Twist"),
    ("topic", "echo", "/cmd_vel", "--once"),
    ("service", "list"),
    ("service", "type", "/param_vel_node/get_parameters"),
    ("service", "find", "rcl_interfaces/srv/GetParameters"),
    ("service", "call", "/param_vel_node/list_parameters", "rcl_interfaces/srv/ListParameters"),
    ("interface", "show", "rcl_interfaces/msg/ParameterDescriptor"),
    ("interface", "list"),
    ("interface", "package", "rcl_interfaces"),
    ("pkg", "prefix", "parameter_tests"),
    ("pkg", "executables", "parameter_tests"),
]


def _every_verb(env: dict[str, str], runs: int) -> None:
    """Terminal medians of every verb: the console script as it was, the venv's `ros2`, and
    `python -c pass` (the interpreter alone, bootstrapper included), interleaved per run."""
    python = str(REPO / ".venv" / "bin" / "python")
    _report(
        "terminal python -S -c pass",
        _timed(lambda: subprocess.run([python, "-S", "-c", "pass"], env=env, check=True), runs),
    )

    def interpreter() -> None:
        subprocess.run([python, "-c", "pass"], env=env, check=True)

    doors = {
        "console script (2 starts)": lambda argv: _terminal(env, *argv, full=True),
        "venv ros2": lambda argv: _terminal(env, *argv),
        "python -c pass": lambda _argv: interpreter(),
    }
    print(f"{'median ms':32s}" + "".join(f"{name:>28s}" for name in doors))
    worst = dict.fromkeys(doors, 0.0)
    for argv in VERBS:
        _terminal(env, *argv)  # warm
        times: dict[str, list[float]] = {name: [] for name in doors}
        for _ in range(runs):  # interleaved: every door sees the same load
            for name, door in doors.items():
                started = time.perf_counter()
                door(argv)
                times[name].append(time.perf_counter() - started)
        medians = {name: statistics.median(t) * 1e3 for name, t in times.items()}
        worst = {name: max(worst[name], medians[name]) for name in doors}
        label = f"ros2 {' '.join(argv[:2])}"
        print(f"{label:32s}" + "".join(f"{medians[name]:28.1f}" for name in doors))
    print(f"{'slowest verb':32s}" + "".join(f"{worst[name]:28.1f}" for name in doors))
    print(f"(n={runs} per verb and door)")


def _not_found(env: dict[str, str], runs: int) -> None:
    """Time `ros2 param get /no_such_node velocity` once the daemon knows the domain."""
    time.sleep(7.0)  # settled: the daemon warm, no process of the domain younger than 6 s
    _report(
        "terminal 'Node not found' (settled)",
        _timed(lambda: _terminal(env, "param", "get", "/no_such_node", "velocity", code=1), runs),
    )


def _first_line(env: dict[str, str], *args: str) -> None:
    """Run a streaming `ros2` command until its first line, then press Ctrl-C."""
    import signal

    proc = subprocess.Popen(
        [str(REPO / ".venv" / "bin" / "ros2"), *args],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        start_new_session=True,
    )
    assert proc.stdout is not None
    line = proc.stdout.readline()
    os.killpg(proc.pid, signal.SIGINT)
    proc.wait(timeout=20)
    proc.stdout.close()
    assert line.startswith("average delay: "), line


def _topic_streams(env: dict[str, str], runs: int) -> None:
    """Time `topic echo` of a missing topic (settled) and `topic delay` (issue 67)."""
    _report(
        "terminal topic echo <missing> (settled)",
        _timed(lambda: _terminal(env, "topic", "echo", "/no_such_topic", code=1), runs),
        "real: 0.29-1.12 s daemon (issue 67), 1.09 s no daemon (golden)",
    )
    _report(
        "terminal topic delay <no header>",
        _timed(lambda: _terminal(env, "topic", "delay", "/cmd_vel", code=1), runs),
        "real: 1.5 s no daemon at least (start, 0.5 s spin, first message)",
    )
    _report(
        "terminal topic delay -> first figures",
        _timed(lambda: _first_line(env, "topic", "delay", "/stamped"), runs),
        "real: 2 s at least (start, 0.5 s spin, 1 s period)",
    )


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
    parser.add_argument("--terminal-only", action="store_true", help="only the terminal part")
    options = parser.parse_args()
    runs = options.runs
    session = get_session()
    env = {**session.env, "PYTHONPATH": str(REPO)}
    env.pop("_ROS_WHEELS_BOOTSTRAP_COMPLETE", None)  # a terminal's environment: not yet set
    daemon = start_daemon(session.env)
    node = session.spawn([sys.executable, str(NODE)], name="vel")
    try:
        assert client().wait_for_node("/param_vel_node", include_hidden=False, timeout=10)
        assert wait_until(lambda: os.path.exists(daemon_socket(session.domain_id)), 15)
        print(f"domain {session.domain_id}, code and `ros2` of {REPO.name}")
        _terminal(env, "node", "list")  # the daemon answers
        _every_verb(env, runs)
        _not_found(env, max(3, runs // 3))
        stamped = session.spawn([sys.executable, str(STAMPED)], name="stamped")
        try:
            assert wait_until(lambda: client().node.count_publishers("/stamped") >= 1, 15)
            time.sleep(7.0)  # settled again: no process of the domain younger than 6 s
            _topic_streams(env, max(3, runs // 3))
        finally:
            stamped.stop()
        if options.terminal_only:
            return
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
