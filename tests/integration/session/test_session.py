"""The session runs the tutorial node in its own domain, and its children die with it."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest
from leftovers import dead_pid, judge_leftover
from rclpy.parameter_client import AsyncParameterClient

from course_lib.core.errors import ExecutableNotFoundError, PackageNotFoundError
from course_lib.core.host.procfs import pid_alive
from course_lib.core.paths import ROSJECT_DIR
from course_lib.processes.orphans import OWNER_ENV, SPAWNED_ENV, command_tag, reap_orphans
from course_lib.ros2.node.client import RosClient
from course_lib.session.session import Session

pytestmark = pytest.mark.ros

PARAMS_FILE = ROSJECT_DIR / "parameter_tests" / "config" / "param_vel_node.yaml"


def velocity_of(session: Session, node: str = "/param_vel_node") -> float:
    """Read the node's velocity as `ros2 param get` does (a read is re-sent until answered:
    a node that has just started may drop the reply to a client it does not know yet)."""
    (value,) = RosClient(session.node, session.wait_future).get_parameters(node, ["velocity"])
    return float(value.value)


def wait_gone(pids: list[int], timeout: float) -> list[int]:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and any(pid_alive(p) for p in pids):
        time.sleep(0.05)
    return [p for p in pids if pid_alive(p)]


def test_tutorial_node_declares_velocity_zero(session: Session) -> None:
    node = session.run("parameter_tests", "param_vel")
    try:
        assert velocity_of(session) == 0.0
        line = node.wait_for_line("Velocity parameter is", timeout=5)
        assert line is not None and line.text.endswith(
            "[param_vel_node]: Velocity parameter is: 0.000000"
        )
    finally:
        assert node.stop() == 0


@pytest.mark.parametrize(
    ("ros_args", "expected"),
    [(["-p", "velocity:=0.3"], 0.3), (["--params-file", "__PARAMS__"], 0.25)],
    ids=["dash-p", "params-file"],
)
def test_start_up_parameters_take_effect(
    session: Session, tmp_path: Path, ros_args: list[str], expected: float
) -> None:
    params = tmp_path / "param_vel_node.yaml"
    params.write_text(PARAMS_FILE.read_text().replace("velocity: 0.0", "velocity: 0.25"))
    args = [str(params) if a == "__PARAMS__" else a for a in ros_args]
    node = session.run("parameter_tests", "param_vel", "--ros-args", *args)
    try:
        assert velocity_of(session) == expected
    finally:
        node.stop()


def test_repo_params_file_loads(session: Session) -> None:
    node = session.run(
        "parameter_tests", "param_vel", "--ros-args", "--params-file", str(PARAMS_FILE)
    )
    try:
        assert velocity_of(session) == 0.0
    finally:
        node.stop()


def test_missing_package_and_executable(session: Session) -> None:
    with pytest.raises(PackageNotFoundError):
        session.run("no_such_pkg", "param_vel")
    with pytest.raises(ExecutableNotFoundError):
        session.run("parameter_tests", "no_such_exec")


def test_two_sessions_never_see_each_other() -> None:
    # Two fresh sessions: the module's own may still list a node an earlier test stopped (a
    # name can outlive its participant in the graph cache: seen for over 30 s once, ros2#1413).
    watcher, other = Session(), Session()
    try:
        assert other.domain_id != watcher.domain_id
        node = other.run("parameter_tests", "param_vel")
        try:
            assert velocity_of(other) == 0.0
            names = watcher.node.get_node_names_and_namespaces()
            assert ("param_vel_node", "/") not in names
            client = AsyncParameterClient(watcher.node, "/param_vel_node")
            assert not client.wait_for_services(timeout_sec=1.0)
        finally:
            node.stop()
    finally:
        other.close()
        watcher.close()


OWNER_SCRIPT = textwrap.dedent(
    """
    import sys
    from course_lib.session.session import Session
    s = Session()
    nodes = [s.run("parameter_tests", "param_vel") for _ in range(2)]
    sleeper = s.spawn([sys.executable, "-c", "import time; time.sleep(600)"], name="sleeper")
    print(" ".join(str(c.pid) for c in [*nodes, sleeper]), flush=True)
    sys.stdin.read()
    """
)


def test_sigkilled_owner_leaves_no_child() -> None:
    with subprocess.Popen(
        [sys.executable, "-c", OWNER_SCRIPT],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    ) as owner:
        pids = [int(p) for p in owner.stdout.readline().split()]
        assert len(pids) == 3 and all(pid_alive(p) for p in pids)
        owner.send_signal(signal.SIGKILL)
        owner.wait()
    assert wait_gone(pids, timeout=2.0) == []


CTRL_C_CHILD = textwrap.dedent(
    """
    import signal, sys, time
    def stopped(number, frame):
        open(sys.argv[1], "w").write(signal.Signals(number).name)
        sys.exit(0)
    signal.signal(signal.SIGINT, stopped)
    open(sys.argv[1], "w").write("started")
    time.sleep(600)
    """
)
EXITING_OWNER = textwrap.dedent(
    """
    import sys, time
    from pathlib import Path
    from course_lib.session.session import Session
    s = Session()
    said = Path(sys.argv[2])
    s.spawn([sys.executable, "-c", sys.argv[1], str(said)], name="ctrl-c child")
    while not (said.exists() and said.read_text() == "started"):
        time.sleep(0.02)
    print("ready", flush=True)
    sys.stdin.read()  # then exit normally, as a kernel does when it is shut down or restarted
    """
)


def test_owner_that_exits_normally_stops_its_children_like_ctrl_c(tmp_path: Path) -> None:
    # A node stopped like Ctrl-C leaves the ROS graph at once; one killed by the death signal
    # (SIGKILL) stays listed until its lease runs out. The spawner thread used to be joined
    # before atexit ran, so every child of an exiting kernel died by SIGKILL.
    said = tmp_path / "signal"
    with subprocess.Popen(
        [sys.executable, "-c", EXITING_OWNER, CTRL_C_CHILD, str(said)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    ) as owner:
        assert owner.stdout.readline().strip() == "ready"
        owner.stdin.close()
        assert owner.wait(timeout=20) == 0
    assert said.read_text() == "SIGINT"


def test_leftovers_of_a_dead_owner_are_reaped() -> None:
    # A child that escaped the death signal (started by hand) but carries a dead owner's tag.
    tag = f"{dead_pid()}:1"
    argv = [sys.executable, "-c", "import time; print('up', flush=True); time.sleep(600)"]
    started: list[subprocess.Popen[str]] = []

    def start() -> subprocess.Popen[str]:
        leftover = subprocess.Popen(
            argv,
            env={**os.environ, OWNER_ENV: tag, SPAWNED_ENV: command_tag(argv)},  # as spawn does
            start_new_session=True,
            stdout=subprocess.PIPE,
            text=True,
        )
        started.append(leftover)
        return leftover

    def reaped_here(leftover: subprocess.Popen[str]) -> bool:
        return leftover.pid in reap_orphans() and leftover.wait(timeout=2) == -signal.SIGKILL

    try:
        # judged once it runs its code: inside the ROS wheels' re-exec its environment reads
        # empty; another session's start may reap it first (leftovers.py)
        assert judge_leftover(start, reaped_here)
    finally:
        for leftover in started:
            if leftover.poll() is None:
                leftover.kill()
            leftover.communicate()


def test_close_stops_children_and_is_idempotent() -> None:
    own = Session()
    node = own.run("parameter_tests", "param_vel")
    own.close()
    own.close()
    assert not node.alive
    assert own.closed


def test_child_stopped_from_elsewhere_never_stays_a_zombie() -> None:
    # Another notebook's lesson (or `make stop`) signals a child this process owns: its owner
    # must reap it without being asked, or every take-over leaves a zombie behind.
    from course_lib.processes.children import spawn

    child = spawn([sys.executable, "-c", "import time; time.sleep(600)"], name="sleeper")
    os.kill(child.pid, signal.SIGKILL)
    deadline = time.monotonic() + 5.0
    stat = Path(f"/proc/{child.pid}/stat")
    while stat.exists() and time.monotonic() < deadline:
        time.sleep(0.02)
    assert not stat.exists(), f"pid {child.pid} is left as {stat.read_text().split()[2]}"


def test_closing_the_current_session_stops_its_nodes_and_the_next_one_is_fresh() -> None:
    from course_lib.session.session import close_current_session, get_session

    first = get_session()
    child = first.run("parameter_tests", "param_vel")
    close_current_session()
    assert first.closed and not child.alive
    close_current_session()  # none open: nothing to do
    second = get_session()
    try:
        assert second is not first and not second.closed and second.children == []
    finally:
        close_current_session()


def test_a_new_session_sweeps_a_port_segment_left_unfinished_first() -> None:
    # Fast DDS waits forever for such a port: the kernel that reached it hung in rclpy.init
    # (course_lib.processes.shm_segments). Port 64999: no participant of a test reaches it.
    port = Path("/dev/shm/fastrtps_port64999")
    port.write_bytes(bytes(52400))  # its first word 0: never made
    hour_ago = time.time() - 3600
    os.utime(port, (hour_ago, hour_ago))
    s = Session()
    try:
        assert not port.exists()
        assert s.node.get_name()  # its own participant came up
    finally:
        s.close()
        port.unlink(missing_ok=True)
