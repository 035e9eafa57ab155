"""Fixtures of the `ros2` integration tests (defined in ros2_golden.py)."""

from ros2_golden import daemon, ros_session

__all__ = ["daemon", "ros_session"]
