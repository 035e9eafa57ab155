"""QoS profiles from ros2topic's `--qos-*` options (imports rclpy when called)."""

from __future__ import annotations

import argparse
from typing import Any

__all__ = ["preset", "qos_from_args"]

_FIELDS = (
    "history",
    "depth",
    "reliability",
    "durability",
    "lifespan",
    "deadline",
    "liveliness",
    "liveliness_lease_duration",
    "avoid_ros_namespace_conventions",
)


def preset(short_key: str) -> Any:
    """Return a copy of rclpy's preset QoS profile `short_key`, free to change.

    rclpy hands out its module-wide preset objects: changing one in a long-lived process (the
    daemon, a kernel) would change `qos_profile_sensor_data` for everything after.
    """
    from rclpy.qos import QoSPresetProfiles, QoSProfile

    shared = QoSPresetProfiles.get_from_short_key(short_key)
    return QoSProfile(**{name: getattr(shared, name) for name in _FIELDS})


def qos_from_args(args: argparse.Namespace) -> Any:
    """Return the preset `--qos-profile` with the other `--qos-*` options applied."""
    from rclpy.duration import Duration
    from rclpy.qos import (
        QoSDurabilityPolicy,
        QoSHistoryPolicy,
        QoSLivelinessPolicy,
        QoSReliabilityPolicy,
    )

    profile = preset(args.qos_profile)
    if args.qos_history:
        profile.history = QoSHistoryPolicy.get_from_short_key(args.qos_history)
    if args.qos_durability:
        profile.durability = QoSDurabilityPolicy.get_from_short_key(args.qos_durability)
    if args.qos_reliability:
        profile.reliability = QoSReliabilityPolicy.get_from_short_key(args.qos_reliability)
    if args.qos_liveliness:
        profile.liveliness = QoSLivelinessPolicy.get_from_short_key(args.qos_liveliness)
    lease = args.qos_liveliness_lease_duration_seconds
    if lease and lease >= 0:
        profile.liveliness_lease_duration = Duration(seconds=lease)
    if args.qos_depth and args.qos_depth >= 0:
        profile.depth = args.qos_depth
    elif profile.durability == QoSDurabilityPolicy.TRANSIENT_LOCAL and profile.depth == 0:
        profile.depth = 1
    return profile
