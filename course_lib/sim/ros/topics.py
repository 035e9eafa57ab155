"""The simulation's hidden reset topics (no ROS import: a kernel's world handle reads them).

Hidden from `ros2 topic list` (a leading underscore): World.reset() sends a number on
RESET_TOPIC and waits for the same number on RESET_DONE_TOPIC.
"""

__all__ = ["RESET_DONE_TOPIC", "RESET_TOPIC"]

RESET_TOPIC = "/_mujoco/reset"
RESET_DONE_TOPIC = "/_mujoco/reset_done"
