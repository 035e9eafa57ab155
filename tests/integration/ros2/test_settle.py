"""A young client waits until it has met the graph; a warm one answers at once.

The wait's rules are unit-tested on a fake clock (tests/unit/ros2/node/test_ros2_discovery.py).
"""

from __future__ import annotations

import time

import pytest

from course_lib.core.waiting import wait_until
from course_lib.ros2.node.client import RosClient
from course_lib.ros2.node.discovery import FASTDDS_DEFAULT_ANNOUNCEMENT_S
from course_lib.session.session import Session

pytestmark = pytest.mark.ros


def _young_client(domain_id: int | None = None) -> tuple[Session, RosClient]:
    session = Session(domain_id=domain_id)
    return session, RosClient(session.node, session.wait_future)


def test_settled_graph_shows_a_node_started_before_the_client(session: Session) -> None:
    child = session.run("parameter_tests", "param_vel")
    owner = RosClient(session.node, session.wait_future)
    try:
        assert wait_until(lambda: "/param_vel_node" in _names(owner), 10)
        late, client = _young_client(session.domain_id)
        try:
            client.settle()
            assert "/param_vel_node" in _names(client)
        finally:
            late.close()
    finally:
        child.stop()


def test_a_warm_client_does_not_wait(session: Session) -> None:
    client = RosClient(session.node, session.wait_future)
    client._born -= 2 * FASTDDS_DEFAULT_ANNOUNCEMENT_S  # as old as a warm daemon's
    started = time.monotonic()
    client.settle()
    # a young client waits for the announcement period (seconds); a warm one only asks the
    # graph once (milliseconds; bounded loosely, so a busy machine never fails it)
    assert time.monotonic() - started < 0.5


def _names(client: RosClient) -> set[str]:
    return {n.full_name for n in client.node_names()}


def test_two_live_namesakes_are_both_listed(session: Session) -> None:
    """The ghost filter (discovery.without_ghosts) never hides a real duplicate: two live
    param_vel_node processes are listed twice, as the real `ros2 node list` does."""
    first = session.run("parameter_tests", "param_vel")
    second = session.run("parameter_tests", "param_vel")
    client = RosClient(session.node, session.wait_future)
    try:

        def twice() -> bool:
            names = [n.full_name for n in client.node_names()]
            return names.count("/param_vel_node") == 2

        assert wait_until(twice, 15), [n.full_name for n in client.node_names()]
        _holders, settled = client._holders()
        assert settled, "every bound participant seen, so the filter did run"
    finally:
        first.stop()
        second.stop()
