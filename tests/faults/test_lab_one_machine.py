"""A lab is one ROS 2 machine: lessons in several kernels share one robot and one node of a name.

Real JupyterLab started as `make lab` starts it, real kernels with the lab's environment (as
JupyterLab gives its kernels), the real simulation.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

import pytest
from jupyter_kernels import Kernel, describe, pid_alive, wait_gone
from lab_server import ARTIFACTS, LabServer

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]


@pytest.fixture(scope="module")
def lab() -> Iterator[LabServer]:
    server = LabServer([], ARTIFACTS / "lab-one-machine")
    try:
        yield server
    finally:
        server.stop()


def _world_pids(kernel: Kernel) -> tuple[int, int]:
    out = kernel.ok("print(world.process.pid, world.viewer.process.pid)").text.split()
    return int(out[0]), int(out[1])


def test_lessons_in_two_kernels_share_one_robot_and_one_node(lab_kernel) -> None:
    six, seven = lab_kernel(), lab_kernel()
    six.ok("from course_lib.lessons import start\nlesson = start(6)\nworld = lesson.world()")
    six.ok("%ros2 run parameter_tests param_vel")
    opened = seven.ok(
        "from course_lib.lessons import start\nlesson = start(7)\nworld = lesson.world()"
    )
    assert "Your lab's robot" in opened.text, opened.everything
    assert _world_pids(six) == _world_pids(seven), "two lessons, two worlds"

    ran = seven.ok("%ros2 run parameter_tests param_vel")
    assert "Stopped /param_vel_node (param_vel) that lesson 6 had started" in ran.text, ran.text
    nodes = seven.ok("%ros2 node list").text
    assert nodes.count("/param_vel_node\n") == 1, nodes
    assert nodes.count("/mujoco\n") == 1, nodes
    assert "share an exact name" not in nodes, nodes

    seven.ok("%ros2 param set /param_vel_node velocity 0.2")
    drove = seven.ok("lesson.drive_for(3.0)").text
    found = re.search(r"says (\d\.\d\d) m/s; the robot drove (\d\.\d) m", drove)
    assert found and found.groups() == ("0.20", "0.6"), drove

    # Lesson 6's kernel goes away: the robot is the lab's, lesson 7 keeps it.
    sim, viewer = _world_pids(seven)
    six.shutdown()
    assert pid_alive(sim) and pid_alive(viewer), "the lab's world died with lesson 6"
    still = seven.ok("lesson.drive_for(1.0)").text
    assert "says 0.20 m/s" in still, still

    # Re-running lesson 7 from the top stops its node, keeps the world and its viewer.
    again = seven.ok("lesson = start(7)\nworld = lesson.world()\nlesson.where()").text
    assert _world_pids(seven) == (sim, viewer)
    assert "speed 0.00 m/s" in again, again
    gone = seven.ok(
        "from course_lib import ros2 as api\nimport time\nt = time.monotonic() + 5\n"
        "while '/param_vel_node' in api.node_list() and time.monotonic() < t: time.sleep(0.05)\n"
        "print('/param_vel_node' in api.node_list())"
    )
    assert gone.text.strip() == "False", "the re-run lesson's node is still listed after 5 s"


def test_a_crashed_lab_world_is_restarted_in_place(lab_kernel) -> None:
    kernel = lab_kernel()
    kernel.ok("from course_lib.lessons import start\nlesson = start(3)\nworld = lesson.world()")
    sim, _ = _world_pids(kernel)
    kernel.ok("import os, signal\nos.kill(world.process.pid, signal.SIGKILL)")
    assert wait_gone([sim], 5.0) == []
    failed = kernel.run("lesson.where()")
    assert "The simulation is not running" in failed.everything, failed.everything
    again = kernel.ok("world = lesson.world()\nlesson.where()")
    assert "The simulation had stopped" in again.text, again.text
    assert "Robot at x" in again.text, again.text
    restarted, viewer = _world_pids(kernel)
    assert restarted != sim
    # The learner's own `world.stop()` stops the lab's world, as lesson 3 says.
    kernel.ok("world.stop()")
    assert wait_gone([restarted, viewer], 10.0) == []


def test_the_labs_own_process_never_loads_the_config_checker(lab_kernel, lab: LabServer) -> None:
    """The lab's process lives as long as the lab: it checks config/ in a child it forks and
    starts the world without reading YAML itself (4 MiB a learner; PyYAML is the checker's)."""
    kernel = lab_kernel()
    kernel.ok("from course_lib.lessons import start\nlesson = start(3)\nworld = lesson.world()")
    assert "/_yaml." not in Path(f"/proc/{lab.process.pid}/maps").read_text()


def test_the_lab_stores_no_live_output(lab: LabServer) -> None:
    """Saving through the lab's Jupyter server (as JupyterLab does) keeps placeholders."""
    import json
    import urllib.request

    import nbformat

    from course_lib.core.files.live_outputs import PLACEHOLDERS
    from course_lib.core.paths import REPO_ROOT

    notebook = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("plot = lesson.speed_plot()")
    widget = {"model_id": "0123", "version_major": 2, "version_minor": 0}
    cell.outputs = [
        nbformat.v4.new_output(
            "display_data",
            data={"application/vnd.jupyter.widget-view+json": widget, "text/plain": "Plot"},
        )
    ]
    notebook.cells.append(cell)
    path = (lab.folder / "saved.ipynb").relative_to(REPO_ROOT)
    body = json.dumps({"type": "notebook", "format": "json", "content": notebook}).encode()
    request = urllib.request.Request(
        f"{lab.base_url}/api/contents/{path}",
        data=body,
        method="PUT",
        headers={"Authorization": f"token {lab.token}", "Content-Type": "application/json"},
    )
    with urllib.request.urlopen(request, timeout=30) as answer:
        assert answer.status in (200, 201)
    stored = nbformat.read(REPO_ROOT / path, as_version=4)
    outputs = stored.cells[0].outputs
    assert [o.data["text/plain"] for o in outputs] == [PLACEHOLDERS["widget"]], outputs


def test_stopping_the_lab_stops_its_world(lab_kernel, lab: LabServer) -> None:
    kernel = lab_kernel()
    kernel.ok("from course_lib.lessons import start\nlesson = start(3)\nworld = lesson.world()")
    sim, viewer = _world_pids(kernel)
    kernel.shutdown()
    lab.stop()
    left = wait_gone([sim, viewer], 10.0)
    assert not left, f"the lab's world outlived the lab:\n{describe(left)}"
