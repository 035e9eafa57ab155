"""Lesson 5, run the node: param_vel_node runs and publishes its velocity on /cmd_vel."""

from __future__ import annotations

from .shared import node_names, own_node_running
from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC"]


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 5's checks: the node runs and publishes 0.0 on /cmd_vel."""
    from ...ros2.api import nodes_and_params as api

    running = own_node_running(lesson) and "/param_vel_node" in node_names()
    speed = api.topic_echo_once("/cmd_vel").linear.x if running else None
    return [
        check("param_vel_node is running", running, "run the `%ros2 run` cell again."),
        check(
            "it publishes its velocity (0.0) on /cmd_vel",
            speed == 0.0,
            "is the node running? `%ros2 node list`",
        ),
    ]


SPEC = LessonSpec(5, "05_run_the_node.ipynb", "Run the node", self_check)
