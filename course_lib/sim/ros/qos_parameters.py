"""`qos_overrides.<topic>.<publisher|subscription>.<policy>` parameters, as ROS 2 nodes show them.

rclpy declares these itself for a publisher or subscription created with
`QoSOverridingOptions`; it does not for the two it creates on its own (the `/parameter_events`
publisher and the `/clock` subscription of a node with `use_sim_time`). For those, the
simulation's nodes declare the same read-only parameters with the QoS actually in use, as the
tutorial's Gazebo nodes (rclcpp) list them.
"""

from __future__ import annotations

from typing import Any

from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node
from rclpy.qos import QoSProfile

__all__ = ["POLICIES", "declare_qos_parameters", "qos_parameter_values"]

POLICIES = ("depth", "durability", "history", "reliability")


def qos_parameter_values(topic: str, entity: str, qos: QoSProfile) -> dict[str, Any]:
    """Return {parameter name: value} for the four policies of one publisher/subscription."""
    prefix = f"qos_overrides.{topic}.{entity}"
    return {
        f"{prefix}.depth": int(qos.depth),
        f"{prefix}.durability": qos.durability.name.lower(),
        f"{prefix}.history": qos.history.name.lower(),
        f"{prefix}.reliability": qos.reliability.name.lower(),
    }


def _entity_qos(node: Node, topic: str, entity: str) -> QoSProfile | None:
    entities = node.publishers if entity == "publisher" else node.subscriptions
    return next((e.qos_profile for e in entities if e.topic_name == topic), None)


def declare_qos_parameters(node: Node, topic: str, entity: str) -> None:
    """Declare the read-only QoS parameters of `node`'s own `entity` on `topic` (if it has one)."""
    qos = _entity_qos(node, topic, entity)
    if qos is None:
        return
    for name, value in qos_parameter_values(topic, entity, qos).items():
        if node.has_parameter(name):
            continue
        policy = name.rsplit(".", 1)[1]
        descriptor = ParameterDescriptor(
            description=f"{policy} of the {entity} on {topic} (read-only, as rclcpp shows it)",
            read_only=True,
        )
        node.declare_parameter(name, value, descriptor)
