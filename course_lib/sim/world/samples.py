"""The robot's state for the course's own readers: /odom's fields and the wheel angles, a few
samples to a message, on a hidden topic (no ROS import here).

A notebook's world handle, live speed plot and replay log read every /odom sample. Three
subscriptions at 50 Hz woke the kernel 150 times a second, and each wake-up costs rclpy about
1 ms of CPU; one message per BATCH_S of simulated time carries the same samples (the same
floats as /odom's) at a tenth of the wake-ups. /odom and /joint_states are unchanged.

A robot at rest for REST_S sends two seconds of samples to a message (REST_BATCH_S): a lab
where the learner reads wakes its kernel every two seconds, not ten times a second. A reader
that needs a recent one asks (sim.ros.topics.FRESH_TOPIC): the waiting samples come at once,
and the next ones every BATCH_S for FRESH_HOLD_S.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

__all__ = [
    "BATCH_S",
    "FIELDS",
    "FRESH_HOLD_S",
    "REST_BATCH_S",
    "REST_S",
    "SAMPLES_TOPIC",
    "RobotSample",
    "batch_size",
    "unpack",
]

SAMPLES_TOPIC = "/_mujoco/samples"  # std_msgs/Float64MultiArray, rows of FIELDS
BATCH_S = 0.1  # simulated seconds of samples in one message
REST_S = 1.0  # simulated seconds at rest before the messages grow to REST_BATCH_S
REST_BATCH_S = 2.0  # simulated seconds of samples in one message of a robot at rest
FRESH_HOLD_S = 2.0  # simulated seconds of BATCH_S messages after a reader asked for fresh ones


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


def batch_size(odom_hz: float, seconds: float = BATCH_S) -> int:
    """Return how many samples one message of `seconds` carries at this /odom rate (>= 1)."""
    return max(1, round(odom_hz * seconds))


def unpack(data: Sequence[float]) -> list[RobotSample]:
    """Return the samples of one message's data (rows of FIELDS; a partial row is dropped)."""
    width = len(FIELDS)
    values = list(data)
    return [RobotSample(*values[i : i + width]) for i in range(0, len(values) - width + 1, width)]
