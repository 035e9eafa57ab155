"""Another node that sets `/param_vel_node`'s velocity with plain rclpy (no door of the course)."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Mapping

__all__ = ["another_node_sets_velocity"]

_SETTER = """
import sys, rclpy
from rclpy.parameter import Parameter
from rclpy.parameter_client import AsyncParameterClient
rclpy.init()
node = rclpy.create_node("other_setter")
client = AsyncParameterClient(node, "/param_vel_node")
assert client.wait_for_services(10.0)
future = client.set_parameters([Parameter("velocity", value=float(sys.argv[1]))])
rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
print(future.result().results[0].successful)
"""


def another_node_sets_velocity(env: Mapping[str, str], value: float) -> None:
    """Set velocity from a process of its own in the domain of `env`; fail if refused."""
    proc = subprocess.run(
        [sys.executable, "-c", _SETTER, str(value)],
        env=dict(env), capture_output=True, text=True, timeout=60, check=False,
    )  # fmt: skip
    assert proc.stdout.strip() == "True", proc.stderr
