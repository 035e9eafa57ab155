"""One world and one driver per lab, whatever lessons ask and whatever runs in a terminal.

Real JupyterLab started as `make lab` starts it, real kernels with the lab's environment, a
real lab terminal, the real simulation.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

import pytest
from jupyter_kernels import Kernel, pid_alive, wait_gone
from lab_server import ARTIFACTS, LabServer
from lab_terminal import RestTerminal

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

START = "from course_lib.lessons import start\nlesson = start({})"
DESCRIPTOR_VEL = "parameter_descriptors descriptor_vel"


@pytest.fixture(scope="module")
def lab() -> Iterator[LabServer]:
    server = LabServer([], ARTIFACTS / "lab-one-world")
    try:
        yield server
    finally:
        server.stop()


def _sim_pid(kernel: Kernel) -> int:
    return int(kernel.ok("print(world.process.pid)").text.split()[0])


def _count(kernel: Kernel, command: str, line: str) -> int:
    return kernel.ok(f"%ros2 {command}").text.splitlines().count(line)


def test_every_world_call_in_a_lab_is_the_labs_one_world(lab_kernel) -> None:
    three, six, other = lab_kernel(), lab_kernel(), lab_kernel()
    three.ok(START.format(3) + "\nworld = lesson.world()")
    # lesson 6 asks for no view: still the lab's world (a second one doubled every node)
    shown = six.ok(START.format(6) + "\nworld = lesson.world(show=False)")
    assert "Your lab's robot" in shown.text, shown.everything
    assert _sim_pid(six) == _sim_pid(three), "lesson 6 started a second world"
    # another real-time factor changes the lab's world in place, in one line
    other.ok("from course_lib.notebook import start_world")
    faster = other.ok("world = start_world(show=False, real_time_factor=2.0)")
    assert _sim_pid(other) == _sim_pid(three), "a real-time factor started a second world"
    said = faster.text.strip().splitlines()
    assert said == [
        "Set the lab's simulation to real_time_factor 2 (it was 1): every notebook of this "
        "lab shares that world."
    ], faster.text
    assert "real_time_factor" not in other.ok("world = start_world(real_time_factor=2)").text
    other.ok("world = start_world(show=False, real_time_factor=1.0)")
    assert _count(three, "node list", "/mujoco") == 1
    # a kernel that only ran its first cell (restarted, say) reads the lab's running world
    fresh = lab_kernel()
    where = fresh.ok(START.format(7) + "\nlesson.where()").text
    assert "Robot at x" in where, where
    assert _sim_pid(three) == int(fresh.ok("print(lesson.current_world.process.pid)").text)
    info = three.ok("%ros2 topic info /clock").text
    assert "Publisher count: 1\n" in info, info


def test_a_lessons_driver_stops_the_other_lessons_drivers_and_names_the_learners(
    lab_kernel, lab: LabServer
) -> None:
    five, eleven = lab_kernel(), lab_kernel()
    five.ok(START.format(5) + "\n%ros2 run parameter_tests param_vel")
    param_vel = int(five.ok("print(lesson.node('param_vel').pid)").text.split()[0])
    eleven.ok(START.format(11) + "\nworld = lesson.world(show=False)")
    ran = eleven.ok(f"%ros2 run {DESCRIPTOR_VEL} --ros-args -p use_sim_time:=true")
    stopped = [line for line in ran.text.splitlines() if line.startswith("Stopped ")]
    assert stopped == [
        "Stopped /param_vel_node (param_vel) that lesson 5 had started: one node at a time "
        "drives your lab's robot."
    ], ran.text
    assert wait_gone([param_vel], 10.0) == [], "lesson 5's param_vel_node still drives"
    assert eleven.ok("print(lesson.self_check().passed)").text  # runs; the exercise is not done
    alone = eleven.ok("print(lesson.self_check())").text
    assert "✓ passed: only your descriptor_vel_node drives the robot" in alone, alone

    terminal = RestTerminal(lab.base_url, lab.token)
    try:
        terminal.run(
            "ros2 topic pub /cmd_vel geometry_msgs/msg/Twist '{linear: {x: 0.0}}'",
            r"publishing #2",
        )
        check = eleven.ok("print(lesson.self_check())").text
        found = re.search(r"✗ not yet: only your descriptor_vel_node .*\n\s+Try: (.*)", check)
        assert found, check
        assert "also publishes on /cmd_vel: stop it (Ctrl-C in its terminal;" in found[1], check
        # another lesson's driver started now leaves the terminal's publisher running, named
        again = eleven.ok(f"%ros2 run {DESCRIPTOR_VEL}")
        named = [line for line in again.text.splitlines() if "also publishes" in line]
        assert len(named) == 1 and "no lesson started it" in named[0], again.text
        terminal.interrupt()
        passed = eleven.ok("print(lesson.self_check())").text
        assert "✓ passed: only your descriptor_vel_node drives the robot" in passed, passed
    finally:
        terminal.close()
    assert pid_alive(int(eleven.ok("print(lesson.node('descriptor_vel').pid)").text.split()[0]))


def _open_sockets() -> int:
    import os

    from course_lib.core.host.procfs import fd_targets

    return sum(target.startswith("socket:") for target in fd_targets(os.getpid()))


def test_a_closed_terminal_leaves_no_socket_in_the_test_process(lab: LabServer) -> None:
    """The tests' terminal closes its websocket for good: one left open (tornado's, freed by
    the garbage collector in whichever test runs then) made pytest fail that other test with
    an "unclosed socket" warning, the suite's one rerun in most full runs."""
    before = _open_sockets()
    for _ in range(3):
        terminal = RestTerminal(lab.base_url, lab.token)
        terminal.run("echo up-$((40 + 2))", r"up-42")
        terminal.close()
    assert _open_sockets() == before
