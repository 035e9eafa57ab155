"""The terminal's `ros2` starts Python once and asks the lab's daemon (issue 23).

The venv's `ros2` is the launcher `make setup` writes (course_lib/ros2/command/quick.py):
Python with `-S`, never rclpy, never re-executed by the ROS wheels' bootstrapper. Every
golden case the daemon serves must print exactly the real tools' text through it; without
a daemon it falls back to the full command; a wrong node name is answered at once once
the daemon knows the whole domain, and a node started just before the command is found.
"""

from __future__ import annotations

import os
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from ros2_golden import GOLDEN, compare, console_env, golden_cases, reset_parameters, start_node
from ros2_golden_part2 import CASES as CASES2
from ros2_golden_part2 import SKIPPED, compare2, names

from course_lib.core.host import procfs
from course_lib.core.paths import WORKSPACE_INSTALL_DIR, venv_bin_dir
from course_lib.core.waiting import wait_until
from course_lib.processes.domain import lease_domain
from course_lib.ros2.command.quick import NO_FALLBACK_ENV, NO_FALLBACK_EXIT, daemon_serves
from course_lib.ros2.node.client import DISCOVERY_WAIT_S, YOUNG_CLIENT_S
from course_lib.ros2.node.connect import daemon_pids, daemon_running, stop_daemon
from course_lib.ros2.node.session_client import client
from course_lib.session.session import session_env

pytestmark = pytest.mark.ros

LAUNCHER = venv_bin_dir() / "ros2"
CASES = golden_cases()
PART2 = {
    name
    for name in {*names("alone"), *names("empty"), *names("four")}
    if name not in SKIPPED
    and (name in names("alone") or CASES2[name]["command"].startswith("ros2 interface"))
}
CASES.update({name: CASES2[name] for name in PART2})


def _argv(command: str) -> list[str]:
    """Return a golden command's argv as a terminal types it to the daemon (the real tools
    print the same with and without their daemon; the goldens were taken without)."""
    return [w for w in shlex.split(command)[1:] if w != "--no-daemon"]


def _fits(case: dict) -> bool:
    """Return whether a case runs with the tutorial node alone or with no node at all."""
    words = case["command"].split()
    alone = any("tutorial node running alone" in note for note in case["notes"])
    return words[0] == "ros2" and (alone or words[1] == "pkg" or case["case"] in PART2)


SERVED = sorted(
    name for name, case in CASES.items() if _fits(case) and daemon_serves(_argv(case["command"]))
)


@pytest.fixture(scope="module")
def tutorial_node(ros_session):  # type: ignore[no-untyped-def]
    child = start_node(ros_session, "param_vel_node.py", "param_vel_node")
    yield child
    child.stop()


def _quick(env: dict[str, str], command: str, **kwargs) -> subprocess.CompletedProcess[str]:  # type: ignore[no-untyped-def]
    return subprocess.run(
        [str(LAUNCHER), *_argv(command)],
        cwd=GOLDEN,
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
        **kwargs,
    )


def test_the_venv_ros2_is_the_one_start_launcher() -> None:
    first = LAUNCHER.read_text().splitlines()[0]
    assert first.endswith(" -S"), f"{LAUNCHER} is not the launcher (`make setup` writes it)"


def test_served_cases_cover_every_daemon_verb_family() -> None:
    families = {" ".join(CASES[name]["command"].split()[1:2]) for name in SERVED}
    assert families >= {"node", "param", "topic", "pkg", "interface"}


@pytest.mark.parametrize("name", SERVED)
def test_golden_case_through_the_daemon(name: str, ros_session, tutorial_node, daemon) -> None:  # type: ignore[no-untyped-def]
    reset_parameters({"param_vel_node"})
    env = {**console_env(ros_session), NO_FALLBACK_ENV: "1"}  # the daemon or a failure
    case = CASES[name]
    if name == "param_dump_after_set":
        assert _quick(env, "ros2 param set /param_vel_node velocity 0.2").returncode == 0
    if name == "pkg_prefix":  # the real tools' prefix was the relative `install`
        case = dict(case, stdout=f"{WORKSPACE_INSTALL_DIR}\n")
    proc = _quick(env, case["command"])
    (compare2 if name in PART2 else compare)(case, (proc.stdout, proc.stderr, proc.returncode))


# What the client must not import: every start of `ros2` would pay for it (on a machine of
# this kind pathlib adds about 7 ms, typing 3.5 ms; rclpy and subprocess are the full command's).
HEAVY = {"pathlib", "typing", "tempfile", "subprocess", "threading", "rclpy"}


def test_a_served_command_imports_nothing_heavy(ros_session, tutorial_node, daemon) -> None:  # type: ignore[no-untyped-def]
    env = {**console_env(ros_session), NO_FALLBACK_ENV: "1", "PYTHONPROFILEIMPORTTIME": "1"}
    proc = _quick(env, "ros2 param get /param_vel_node velocity")
    assert proc.stdout == "Double value is: 0.0\n" and proc.returncode == 0, proc.stderr[-2000:]
    imported = {
        line.split("|")[-1].strip()
        for line in proc.stderr.splitlines()
        if line.startswith("import time:")
    }
    assert "course_lib.ros2.node.wire" in imported  # the profile covers the client's imports
    assert not imported & HEAVY, f"the terminal's client imported {sorted(imported & HEAVY)}"


def _maps(pid: int) -> str:
    with open(f"/proc/{pid}/maps") as handle:
        return handle.read()


def test_a_streaming_command_runs_in_one_python_without_rclpy_and_stops_on_ctrl_c(  # type: ignore[no-untyped-def]
    ros_session, tutorial_node, daemon
) -> None:
    env = {**console_env(ros_session), NO_FALLBACK_ENV: "1"}
    env.pop("_ROS_WHEELS_BOOTSTRAP_COMPLETE", None)  # a terminal's: the wheels' marker unset
    with subprocess.Popen(
        [str(LAUNCHER), "topic", "echo", "/cmd_vel", "--field", "linear.x"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    ) as proc:
        try:
            assert proc.stdout is not None
            assert proc.stdout.readline() == "0.0\n"  # the stream flows
            with open(f"/proc/{proc.pid}/environ", "rb") as handle:
                environ = handle.read().split(b"\0")
            assert not any(v.startswith(b"_ROS_WHEELS_BOOTSTRAP_COMPLETE=") for v in environ)
            assert "librcl" not in _maps(proc.pid)  # rclpy was never loaded
            proc.send_signal(signal.SIGINT)
            assert proc.wait(10) == 2
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.wait()


@pytest.fixture
def no_daemon_domain():  # type: ignore[no-untyped-def]
    """Yield a terminal's environment in a leased domain where no daemon runs (yet)."""
    lease = lease_domain({})
    env = {**session_env(lease.domain_id), "PYTHONPATH": str(GOLDEN.parents[2]), "COLUMNS": "80"}
    try:
        yield env
    finally:
        stop_daemon(lease.domain_id)
        lease.release()


def test_without_a_daemon_the_full_command_answers(no_daemon_domain) -> None:  # type: ignore[no-untyped-def]
    env = no_daemon_domain
    domain = env["ROS_DOMAIN_ID"]
    assert not daemon_running(domain)
    refused = _quick({**env, NO_FALLBACK_ENV: "1"}, "ros2 node list")
    assert (refused.returncode, refused.stdout) == (NO_FALLBACK_EXIT, "")
    case = CASES["interface_show_parameter_descriptor"]
    shown = _quick(env, case["command"])  # a non-graph verb: run in the terminal
    assert (shown.stdout, shown.stderr, shown.returncode) == (
        case["stdout"],
        case["stderr"],
        case["exit"],
    )
    assert not daemon_running(domain)
    listed = _quick(env, "ros2 node list")  # a graph verb: the full command starts a daemon
    assert (listed.stdout, listed.stderr, listed.returncode) == ("", "", 0)
    assert daemon_running(domain)


def test_wrong_node_name_is_answered_at_once_when_the_domain_is_settled(  # type: ignore[no-untyped-def]
    ros_session, tutorial_node, daemon
) -> None:
    assert wait_until(client().graph_complete, 20), "the domain never settled"
    env = {**console_env(ros_session), NO_FALLBACK_ENV: "1"}
    assert wait_until(lambda: _quick(env, "ros2 node list").returncode == 0, 10)
    started = time.monotonic()
    proc = _quick(env, "ros2 param get /no_such_node velocity")
    took = time.monotonic() - started
    assert (proc.stdout, proc.stderr, proc.returncode) == ("", "Node not found\n", 1)
    # before: at least DISCOVERY_WAIT_S, always (a bound loose enough for a loaded machine)
    assert took < DISCOVERY_WAIT_S, took


@pytest.mark.parametrize("round_", range(5))
def test_a_node_started_just_before_the_command_is_found(ros_session, daemon, round_) -> None:  # type: ignore[no-untyped-def]
    assert wait_until(client().graph_complete, 20), "the domain never settled"
    env = {**console_env(ros_session), NO_FALLBACK_ENV: "1"}
    script = str(GOLDEN / "nodes" / "param_vel_node.py")
    rename = ["--ros-args", "-r", "__node:=late_vel_node"]
    child = ros_session.spawn([sys.executable, script, *rename], name="late_vel")
    try:
        proc = _quick(env, "ros2 param get /late_vel_node velocity")
        assert (proc.stdout, proc.stderr, proc.returncode) == ("Double value is: 0.0\n", "", 0)
    finally:
        child.stop()


def test_launch_of_a_missing_package_lists_only_the_callers_prefixes(tmp_path) -> None:  # type: ignore[no-untyped-def]
    env = {k: v for k, v in os.environ.items() if not k.startswith("_ROS_WHEELS")}
    env.update({"AMENT_PREFIX_PATH": f"{tmp_path}:{sys.prefix}", "ROS_DOMAIN_ID": ""})
    proc = subprocess.run(
        [str(LAUNCHER), "launch", "no_such_pkg", "param_vel.launch.py"],
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    case = CASES["launch_missing_package"]
    expected = case["stderr"].replace("['install', '<venv>']", repr([str(tmp_path), sys.prefix]))
    assert (proc.stdout, proc.stderr, proc.returncode) == ("", expected, case["exit"])


# A node whose constructor pauses between its parameter services and its publisher, as one
# starved on a busy host does (ci74: the graph held still longer than the daemon waited for a
# newcomer, and `ros2 topic info` said "Unknown topic" of a node started moments before).
PAUSED_NODE = """
import time, rclpy
from geometry_msgs.msg import Twist
rclpy.init()
node = rclpy.create_node("paused_vel_node")
time.sleep(1.5)
node.create_publisher(Twist, "paused_cmd_vel", 10)
rclpy.spin(node)
"""


def _daemon_age(domain: int) -> float:
    """Return how long the domain's daemon has run (s)."""
    (pid,) = daemon_pids(domain)
    uptime = float(Path("/proc/uptime").read_text().split()[0])
    return uptime - int(procfs.start_time(pid) or 0) / os.sysconf("SC_CLK_TCK")


def test_a_node_whose_constructor_pauses_is_counted_whole(ros_session, daemon) -> None:  # type: ignore[no-untyped-def]
    assert wait_until(client().graph_complete, 20), "the domain never settled"
    env = {**console_env(ros_session), NO_FALLBACK_ENV: "1"}
    # a warm daemon's case: a younger one looks for a name it does not know yet anyway
    time.sleep(max(0.0, YOUNG_CLIENT_S + 0.5 - _daemon_age(ros_session.domain_id)))
    child = ros_session.spawn([sys.executable, "-c", PAUSED_NODE], name="paused_vel")
    try:
        info = _quick(env, "ros2 topic info /paused_cmd_vel")
    finally:
        child.stop()
    expected = "Type: geometry_msgs/msg/Twist\nPublisher count: 1\nSubscription count: 0\n"
    assert (info.stdout, info.stderr, info.returncode) == (expected, "", 0)


@pytest.mark.parametrize("round_", range(3))
def test_a_command_moments_after_a_node_starts_counts_all_of_it(
    ros_session, daemon, round_
) -> None:  # type: ignore[no-untyped-def]
    assert wait_until(client().graph_complete, 20), "the domain never settled"
    env = {**console_env(ros_session), NO_FALLBACK_ENV: "1"}
    script = str(GOLDEN / "nodes" / "param_vel_node.py")
    names = ["--ros-args", "-r", "__node:=fresh_vel_node", "-r", "cmd_vel:=fresh_cmd_vel"]
    child = ros_session.spawn([sys.executable, script, *names], name="fresh_vel")
    try:
        info = _quick(env, "ros2 topic info /fresh_cmd_vel")
        services = _quick(env, "ros2 service list")
    finally:
        child.stop()
    expected = "Type: geometry_msgs/msg/Twist\nPublisher count: 1\nSubscription count: 0\n"
    assert (info.stdout, info.stderr, info.returncode) == (expected, "", 0)
    assert services.stdout.count("/fresh_vel_node/") == 7, services.stdout
