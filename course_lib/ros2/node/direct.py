"""A client node of one process, as ros2cli's DirectNode: `--no-daemon` commands and the daemon.

It has its own rclpy context and a spin thread, no signal handlers and no parameter
services; `use_sim_time` is set as `--use-sim-time` asks.
"""

from __future__ import annotations

import os
from typing import Any

from ...session.session import SpinningNode

__all__ = ["DirectNode", "cli_node_name", "daemon_node_name"]

NODE_NAME_PREFIX = "_ros2cli"


def cli_node_name(pid: int | None = None) -> str:
    """Return the name ros2cli gives a command's own node: `_ros2cli_<pid>`."""
    return f"{NODE_NAME_PREFIX}_{os.getpid() if pid is None else pid}"


def daemon_node_name(domain_id: int) -> str:
    """Return a daemon node's name as ros2cli's: `_ros2cli_daemon_<domain>_<random hex>`."""
    import uuid

    return f"{NODE_NAME_PREFIX}_daemon_{domain_id}_{uuid.uuid4().hex}"


class DirectNode(SpinningNode):
    """The command's node in its own context, spinning in a background thread until close()."""

    def __init__(
        self, *, domain_id: int, node_name: str | None = None, use_sim_time: bool = False
    ) -> None:
        from rclpy.parameter import Parameter

        super().__init__(
            node_name or cli_node_name(),
            domain_id=domain_id,
            owner="the ros2 command's",
            thread_name="ros2cli-spin",
            parameter_overrides=[Parameter("use_sim_time", value=use_sim_time)],
        )

    def client(self) -> Any:
        """Return a RosClient over this node, whose age counts from the node's birth."""
        from .client import RosClient

        return RosClient(self.node, self.wait_future, born=self.born)
