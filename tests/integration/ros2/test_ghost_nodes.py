"""A node that has left is gone from every answer, even when the graph keeps its name.

rmw's graph can keep a node's name with no participant behind it (ros2/ros2#1413): CI saw lesson
2's `%ros2 param list /param_vel_node`, run after the node was stopped, wait 5 s and print
"Wait for service timed out ..." instead of "Node not found", and a stopped node still listed
after 5 s and after 30 s. `ghost_node.make_ghost` puts such a name into the running clients'
graphs through rmw's own API, so these tests see the real graph cache with a real ghost.
"""

from __future__ import annotations

import time

import pytest
from ghost_node import make_ghost
from ros2_golden import console_env, run_console

from course_lib.core.waiting import wait_until
from course_lib.ros2.api import nodes_and_params as api
from course_lib.ros2.node.client import SERVICE_WAIT_S
from course_lib.ros2.node.discovery import GHOST_GRACE_S
from course_lib.session.session import Session

pytestmark = pytest.mark.ros


def _raw(session: Session) -> list[str]:
    """The graph's own node list (as rclpy returns it), ghosts included."""
    return [ns.rstrip("/") + "/" + n for n, ns in session.node.get_node_names_and_namespaces()]


def _ghost(session: Session, name: str) -> None:
    make_ghost(session.domain_id, name, heard=lambda: f"/{name}" in _raw(session))
    time.sleep(GHOST_GRACE_S)  # listed that long with no participant: a ghost


def test_a_ghost_is_neither_listed_nor_found(lab: Session) -> None:
    _ghost(lab, "param_vel_node")
    assert "/param_vel_node" in _raw(lab), "the graph keeps the ghost's name"

    assert "/param_vel_node" not in api.node_list()
    started = time.monotonic()
    out = api.ros2("ros2 param list /param_vel_node")
    took = time.monotonic() - started
    assert (out.stdout, out.exit_code) == ("", 1), out
    assert out.stderr.startswith("Node not found"), out
    # The defect this guards against waited SERVICE_WAIT_S for the ghost's services. The answer
    # takes 0.9 s on a quiet machine (the helper's own participant leaves the graph first) and
    # took 2.1 s once on 2 busy cores (ci77), against the 2.0 s this bound was.
    assert took < SERVICE_WAIT_S - 1.0, f"'Node not found' after {took:.1f} s"

    stdout, _err, code = run_console(console_env(lab), "ros2 node list")
    assert code == 0 and "/param_vel_node" not in stdout, stdout


def test_a_node_started_under_a_ghosts_name_is_listed_once(lab: Session) -> None:
    _ghost(lab, "param_vel_node")
    child = lab.run("parameter_tests", "param_vel")
    try:
        assert wait_until(lambda: "/param_vel_node" in api.node_list(), 10), api.node_list()
        assert api.node_list().count("/param_vel_node") == 1, api.node_list()
        stdout, _err, code = run_console(
            console_env(lab), "ros2 param get /param_vel_node velocity"
        )
        assert (stdout, code) == ("Double value is: 0.0\n", 0)
    finally:
        child.stop()
    assert wait_until(lambda: "/param_vel_node" not in api.node_list(), 10), api.node_list()
