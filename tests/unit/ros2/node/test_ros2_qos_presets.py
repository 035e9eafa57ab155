"""`--qos-*` options never change rclpy's shared presets (the daemon and kernels live long)."""

from __future__ import annotations

import argparse

from rclpy.qos import QoSReliabilityPolicy, qos_profile_sensor_data

from course_lib.ros2.node.qos import qos_from_args


def test_overrides_leave_the_shared_preset_alone() -> None:
    args = argparse.Namespace(
        qos_profile="sensor_data",
        qos_history=None,
        qos_durability="transient_local",
        qos_reliability="reliable",
        qos_liveliness=None,
        qos_liveliness_lease_duration_seconds=None,
        qos_depth=3,
    )
    profile = qos_from_args(args)
    assert profile.reliability == QoSReliabilityPolicy.RELIABLE and profile.depth == 3
    assert qos_profile_sensor_data.reliability == QoSReliabilityPolicy.BEST_EFFORT
    assert qos_profile_sensor_data.depth == 5
