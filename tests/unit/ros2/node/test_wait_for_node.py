"""`wait_for_node` (GraphClient's) decides on its last look, not on one before the graph grew.

A node's participant can answer while the client takes the view that ends the wait (seen in
the suite: a starved process resumed, "not found after 6.2 s" with the node in the graph). The
graph here is scripted: the node arrives while the deciding view is taken. The clock is
scripted too: on a busy host real sleeps overshoot, and the quiet time ran out a poll before
the node's call (the fresh-clone suite failed here three times of three).
"""

from __future__ import annotations

import pytest
from fake_clock import FakeClock

from course_lib.ros2.node import graph_client as graph_module
from course_lib.ros2.node.discovery import GraphView
from course_lib.ros2.node.graph_client import GraphClient
from course_lib.ros2.results import NodeName

NODE = NodeName("param_vel_node", "/", "/param_vel_node")
ALL_SEEN = GraphView(frozenset(), frozenset(), unknown_endpoints=0, missing_participants=0)


class _ArrivingGraph(GraphClient):
    """A warm client whose graph gains the node as the wait's deciding view is taken."""

    def __init__(self, arrives_in: str) -> None:  # no rclpy node: the graph is scripted
        self.node = None  # no quick look (LiveGraphNode.listed_and_running): the views decide
        self.arrives_in = arrives_in
        self.arrived = False
        self.complete_calls = 0
        self.time = FakeClock(1000.0)

    def wait(self, timeout: float) -> bool:
        """The wait a `ros2` command makes for the tutorial node, on the scripted clock."""
        return self.wait_for_node(
            "/param_vel_node", include_hidden=False, timeout=timeout,
            clock=self.time.clock, sleep=self.time.sleep,
        )  # fmt: skip

    def age(self) -> float:
        return 60.0

    def node_names(self, *, include_hidden: bool = False) -> list[NodeName]:
        return [NODE] if self.arrived else []

    def graph_view(self) -> GraphView:
        self.arrived = self.arrived or self.arrives_in == "view"
        return ALL_SEEN

    def graph_complete(self) -> bool:
        self.complete_calls += 1  # complete from the start; the node comes on a late call
        self.arrived = self.arrived or (self.arrives_in == "complete" and self.complete_calls > 8)
        return True


@pytest.fixture
def short_waits(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(graph_module, "DISCOVERY_WAIT_S", 0.05)
    monkeypatch.setattr(graph_module, "YOUNG_CLIENT_S", 0.0)
    monkeypatch.setattr(graph_module, "SETTLED_QUIET_S", 0.15)


def test_a_node_that_arrives_with_the_deadlines_view_is_found(short_waits: None) -> None:
    graph = _ArrivingGraph("view")
    graph.graph_complete = lambda: False  # type: ignore[method-assign]
    assert graph.wait(timeout=0)


def test_a_node_that_arrives_as_the_graph_is_found_complete_is_found(short_waits: None) -> None:
    graph = _ArrivingGraph("complete")
    assert graph.wait(timeout=5)


def test_a_node_absent_from_a_complete_graph_is_not_found(short_waits: None) -> None:
    graph = _ArrivingGraph("never")
    assert not graph.wait(timeout=0)
