"""Compare the simulation's topics with the tutorial's Gazebo world (lesson 3).

`compare_with_tutorial()` is pure (names in, text out); `compare_topics()` asks the running
ROS graph through the `ros2` Python API.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

__all__ = ["TUTORIAL_TOPICS", "TopicComparison", "compare_topics", "compare_with_tutorial"]

# `ros2 topic list` in the tutorial's Gazebo TurtleBot3 Waffle Pi world.
TUTORIAL_TOPICS = (
    "/camera/camera_info",
    "/camera/image_raw",
    "/clock",
    "/cmd_vel",
    "/imu",
    "/joint_states",
    "/odom",
    "/parameter_events",
    "/performance_metrics",
    "/robot_description",
    "/rosout",
    "/scan",
    "/tf",
    "/tf_static",
)
WHY_MISSING = {
    "/performance_metrics": (
        "Gazebo's own message (gazebo_msgs/msg/PerformanceMetrics): how fast Gazebo runs.",
        "MuJoCo is not Gazebo; here /mujoco's real_time_factor parameter sets that speed.",
    ),
}


@dataclass(frozen=True)
class TopicComparison:
    """Which of the tutorial's topics this world has, and what differs."""

    shared: tuple[str, ...]
    only_tutorial: tuple[str, ...]
    only_here: tuple[str, ...]

    def __repr__(self) -> str:
        lines = [
            f"Topics of the tutorial's Gazebo world also here: {len(self.shared)} "
            f"of {len(self.shared) + len(self.only_tutorial)}"
        ]
        for name in self.only_tutorial:
            lines.append(f"Only in the tutorial: {name}")
            lines += [f"  {why}" for why in WHY_MISSING.get(name, ("not simulated here",))]
        lines.append(f"Only here: {', '.join(self.only_here) or 'nothing'}")
        return "\n".join(lines) + "\n"


def compare_with_tutorial(names: Iterable[str]) -> TopicComparison:
    """Return how the topic `names` differ from the tutorial's list."""
    here = set(names)
    tutorial = set(TUTORIAL_TOPICS)
    return TopicComparison(
        shared=tuple(sorted(here & tutorial)),
        only_tutorial=tuple(sorted(tutorial - here)),
        only_here=tuple(sorted(here - tutorial)),
    )


def compare_topics() -> TopicComparison:
    """Compare the topics `ros2 topic list` shows now with the tutorial's."""
    from ..ros2.api import nodes_and_params as api

    return compare_with_tutorial(topic.name for topic in api.topic_list())
