"""A young client waits for the graph to settle, not a fixed second."""

from __future__ import annotations

import time

import pytest

from course_lib.ros2.client import GRAPH_QUIET_S, GRAPH_SETTLE_S, RosClient, wait_until
from course_lib.session import Session

pytestmark = pytest.mark.ros


def _young_client(domain_id: int | None = None) -> tuple[Session, RosClient]:
    session = Session(domain_id=domain_id)
    return session, RosClient(session.node, session.wait_future)


def test_settle_ends_once_the_graph_is_quiet() -> None:
    session, client = _young_client()
    try:
        started = time.monotonic()
        client.settle()
        took = time.monotonic() - started
        # A fixed wait would last until the client is GRAPH_SETTLE_S old.
        assert GRAPH_QUIET_S <= took < GRAPH_QUIET_S + (GRAPH_SETTLE_S - GRAPH_QUIET_S) / 2
    finally:
        session.close()


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
    client._born -= GRAPH_SETTLE_S
    started = time.monotonic()
    client.settle()
    assert time.monotonic() - started < 0.05


def _names(client: RosClient) -> set[str]:
    return {n.full_name for n in client.node_names()}
