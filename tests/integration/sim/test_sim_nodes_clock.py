"""Tripwire: the simulation's nodes keep `use_sim_time` but do not subscribe their own /clock."""

from __future__ import annotations

import pytest
from rclpy.node import Node
from rclpy.parameter import Parameter

from course_lib.session.session import Session
from course_lib.sim.ros.nodes import NodeSpec, create_nodes

pytestmark = pytest.mark.ros


def _subscribed_topics(node: Node) -> set[str]:
    pairs = node.get_subscriber_names_and_types_by_node(node.get_name(), node.get_namespace())
    return {name for name, _types in pairs}


def test_a_sim_time_node_subscribes_clock(session: Session) -> None:
    """What create_nodes undoes: rclpy subscribes /clock for use_sim_time (else update it)."""
    node = Node(
        "clock_probe_plain",
        context=session.context,
        parameter_overrides=[Parameter("use_sim_time", value=True)],
    )
    try:
        assert "/clock" in _subscribed_topics(node)
    finally:
        node.destroy_node()


def test_sim_nodes_have_no_clock_subscription(session: Session) -> None:
    nodes = create_nodes(session.context, [NodeSpec("clock_probe_sim", True, {})])
    node = nodes["clock_probe_sim"]
    try:
        assert node.get_parameter("use_sim_time").value is True
        assert "/clock" not in _subscribed_topics(node), (
            "rclpy changed how a node follows /clock: update _drop_own_clock_subscription "
            "in course_lib/sim/ros/nodes.py"
        )
    finally:
        node.destroy_node()
