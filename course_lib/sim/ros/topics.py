"""The simulation's hidden request topics (no ROS import: a kernel's world handle uses them).

Hidden from `ros2 topic list` (a leading underscore): World.reset() sends a number on
RESET_TOPIC and waits for the same number on RESET_DONE_TOPIC. A reader that finds its
latest sample old sends an empty message on FRESH_TOPIC: a robot at rest sends its samples
every two seconds (sim.world.samples), and asked, sends those that wait at once and the next
ones every BATCH_S for a while.
"""

from typing import Any

__all__ = ["FRESH_TOPIC", "RESET_DONE_TOPIC", "RESET_TOPIC", "reset_done_qos"]

FRESH_TOPIC = "/_mujoco/fresh"  # std_msgs/Empty
RESET_TOPIC = "/_mujoco/reset"
RESET_DONE_TOPIC = "/_mujoco/reset_done"


def reset_done_qos() -> Any:
    """Return RESET_DONE_TOPIC's QoS, the same on both sides: transient local, the last ten
    numbers kept. A kernel sees the simulation's publisher before the simulation has matched
    the kernel's subscription (each side discovers the other on its own), and a volatile
    reply sent in between would reach no one: the kernel would wait for a reset already done."""
    from rclpy.qos import DurabilityPolicy, QoSProfile

    return QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)
