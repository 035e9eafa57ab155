"""`%ros2 run` of a node that takes longer than usual to start shows its first line.

On a busy hub a node's Python, rclpy and the node itself can take more than the magic's
usual 3 s to say their first line; a line that comes after the magic returns is shown
nowhere. Here the node's interpreter is made slow with a `sitecustomize` that sleeps as
it starts (once: the ROS wheels' bootstrapper re-executes Python before `site` imports it).
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from course_lib.core.waiting import wait_until
from course_lib.notebook.magics import RUN_FIRST_WAIT_S, SLOW_START_WAIT_S, run_line
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import get_session

pytestmark = [pytest.mark.ros]

# The magic waited RUN_FIRST_WAIT_S for a first line, then up to 5 s more for a node of the
# process to show whether it drives the robot: a start slower than both was shown nowhere.
SLOW_S = 9.0


@pytest.fixture
def slow_python(tmp_path: Path) -> Iterator[Callable[[float], None]]:
    """Slow down the start of the session's children's Python by the given seconds."""
    session = get_session()
    before = session.env.get("PYTHONPATH")
    running = {child.pid for child in session.children}

    def slow(seconds: float) -> None:
        (tmp_path / "sitecustomize.py").write_text(f"import time\ntime.sleep({seconds})\n")
        session.env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(tmp_path), before]))

    try:
        yield slow
    finally:
        if before is None:
            session.env.pop("PYTHONPATH", None)
        else:
            session.env["PYTHONPATH"] = before
        for child in session.children:
            if child.pid not in running:  # the test's own nodes, nothing else
                child.stop()


def test_a_node_slow_to_start_has_its_first_line_shown(
    slow_python: Callable[[float], None],
) -> None:
    assert RUN_FIRST_WAIT_S + 5.0 < SLOW_S < SLOW_START_WAIT_S - 3.0
    slow_python(SLOW_S)
    began = time.monotonic()
    result = run_line("run parameter_tests param_vel")
    took = time.monotonic() - began
    assert "Velocity parameter is" in result.output.text, (took, result.output)
    assert took < SLOW_START_WAIT_S + 3.0, took
    assert wait_until(lambda: "/param_vel_node" in api.node_list(), 10.0)


def test_a_silent_node_ends_the_wait_once_the_graph_lists_it(
    slow_python: Callable[[float], None],
) -> None:
    """A node that prints nothing (its log level above INFO) is not waited for to the limit."""
    slow_python(3.0)
    began = time.monotonic()
    result = run_line("run parameter_tests param_vel --ros-args --log-level fatal")
    took = time.monotonic() - began
    assert result.output.exit_code == 0, result.output
    assert result.output.text == "", result.output
    assert took < SLOW_START_WAIT_S - 3.0, took
    assert "/param_vel_node" in api.node_list()


def test_a_rerun_cell_shows_the_new_nodes_first_line(
    slow_python: Callable[[float], None],
) -> None:
    """Run twice, as a re-run cell does: the first node (already in the graph) is stopped,
    and only the new, slow one's own first line ends the wait."""
    assert "Velocity parameter is" in run_line("run parameter_tests param_vel").output.text
    slow_python(SLOW_S)
    result = run_line("run parameter_tests param_vel")
    assert "Velocity parameter is" in result.output.text, result.output
    assert wait_until(lambda: api.node_list().count("/param_vel_node") == 1, 10.0)
