"""Differential-drive kinematics of the TurtleBot3 (pure: no MuJoCo, no rclpy).

Lesson 7 drives the robot with `velocity`: the node publishes a twist on `/cmd_vel`, and the
simulation turns it into wheel speeds with `DiffDrive.wheel_speeds`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["DiffDrive", "Pose2D", "quat_from_yaw", "wrap_angle", "yaw_from_quat"]


@dataclass(frozen=True)
class Pose2D:
    """A pose on the floor: position in metres, heading in radians (counter-clockwise)."""

    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0


@dataclass(frozen=True)
class DiffDrive:
    """Two driven wheels on one axle: convert body twists to wheel speeds and back."""

    wheel_radius_m: float = 0.033
    wheel_separation_m: float = 0.287

    def __post_init__(self) -> None:
        if self.wheel_radius_m <= 0 or self.wheel_separation_m <= 0:
            raise ValueError(
                f"wheel radius ({self.wheel_radius_m} m) and separation "
                f"({self.wheel_separation_m} m) must be positive"
            )

    def wheel_speeds(self, linear_mps: float, angular_radps: float) -> tuple[float, float]:
        """Return (left, right) wheel speeds in rad/s for a forward speed and a yaw rate."""
        half = angular_radps * self.wheel_separation_m / 2.0
        return (
            (linear_mps - half) / self.wheel_radius_m,
            (linear_mps + half) / self.wheel_radius_m,
        )

    def body_twist(self, left_radps: float, right_radps: float) -> tuple[float, float]:
        """Return (forward speed m/s, yaw rate rad/s) for the given wheel speeds."""
        left = left_radps * self.wheel_radius_m
        right = right_radps * self.wheel_radius_m
        return (left + right) / 2.0, (right - left) / self.wheel_separation_m


def wrap_angle(angle: float) -> float:
    """Return the angle wrapped into [-pi, pi)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def yaw_from_quat(w: float, x: float, y: float, z: float) -> float:
    """Return the heading (rotation about z) of a unit quaternion (w, x, y, z)."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def quat_from_yaw(yaw: float) -> tuple[float, float, float, float]:
    """Return the unit quaternion (w, x, y, z) of a rotation by `yaw` about z."""
    return math.cos(yaw / 2.0), 0.0, 0.0, math.sin(yaw / 2.0)
