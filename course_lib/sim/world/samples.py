"""The robot's state for the course's own readers: /odom's fields and the wheel angles, a few
samples to a message, on a hidden topic (no ROS import here).

A notebook's world handle, live speed plot and replay log read every /odom sample. Three
subscriptions at 50 Hz woke the kernel 150 times a second, and each wake-up costs rclpy about
1 ms of CPU; one message per BATCH_S of simulated time carries the same samples (the same
floats as /odom's) at a tenth of the wake-ups. /odom and /joint_states are unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

__all__ = ["BATCH_S", "FIELDS", "SAMPLES_TOPIC", "RobotSample", "batch_size", "unpack"]

SAMPLES_TOPIC = "/_mujoco/samples"  # std_msgs/Float64MultiArray, rows of FIELDS
BATCH_S = 0.1  # simulated seconds of samples in one message


class RobotSample(NamedTuple):
    """One /odom sample (its stamp, pose, forward speed, yaw rate) and the wheel angles."""

    time_s: float
    x: float
    y: float
    qw: float
    qx: float
    qy: float
    qz: float
    linear_mps: float
    angular_radps: float
    wheel_left_rad: float
    wheel_right_rad: float


FIELDS = RobotSample._fields


def batch_size(odom_hz: float) -> int:
    """Return how many samples one message carries at this /odom rate (at least one)."""
    return max(1, round(odom_hz * BATCH_S))


def unpack(data: Sequence[float]) -> list[RobotSample]:
    """Return the samples of one message's data (rows of FIELDS; a partial row is dropped)."""
    width = len(FIELDS)
    values = list(data)
    return [RobotSample(*values[i : i + width]) for i in range(0, len(values) - width + 1, width)]
