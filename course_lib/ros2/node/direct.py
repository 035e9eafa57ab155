"""A client node of one process, as ros2cli's DirectNode: `--no-daemon` commands and the daemon.

It has its own rclpy context and a spin thread, no signal handlers and no parameter
services; `use_sim_time` is set as `--use-sim-time` asks.
"""

from __future__ import annotations

import contextlib
import logging
import os
import threading
import time
from typing import Any

_log = logging.getLogger(__name__)

__all__ = ["DirectNode", "cli_node_name", "daemon_node_name"]

NODE_NAME_PREFIX = "_ros2cli"


def cli_node_name(pid: int | None = None) -> str:
    """Return the name ros2cli gives a command's own node: `_ros2cli_<pid>`."""
    return f"{NODE_NAME_PREFIX}_{os.getpid() if pid is None else pid}"


def daemon_node_name(domain_id: int) -> str:
    """Return a daemon node's name as ros2cli's: `_ros2cli_daemon_<domain>_<random hex>`."""
    import uuid

    return f"{NODE_NAME_PREFIX}_daemon_{domain_id}_{uuid.uuid4().hex}"


class DirectNode:
    """One rclpy node in its own context, spinning in a background thread until close()."""

    def __init__(
        self, *, domain_id: int, node_name: str | None = None, use_sim_time: bool = False
    ) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.parameter import Parameter
        from rclpy.signals import SignalHandlerOptions

        self.context = rclpy.Context()
        rclpy.init(
            context=self.context,
            domain_id=domain_id,
            signal_handler_options=SignalHandlerOptions.NO,
        )
        self.born = time.monotonic()  # the DDS participant comes with the first node
        self.node = rclpy.create_node(
            node_name or cli_node_name(),
            context=self.context,
            start_parameter_services=False,
            parameter_overrides=[Parameter("use_sim_time", value=use_sim_time)],
        )
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self._thread = threading.Thread(target=self._spin, name="ros2cli-spin", daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        try:
            self.executor.spin()
        except Exception as err:
            if self.context.ok():  # not the context shutting down: say so, with traceback
                _log.error("the ros2 command's ROS thread stopped", exc_info=err)

    def wait_future(self, future: Any, timeout: float) -> Any:
        """Wait for a future completed by the spin thread; raise TimeoutError."""
        done = threading.Event()
        future.add_done_callback(lambda _f: done.set())
        if not done.wait(timeout):
            future.cancel()
            raise TimeoutError(f"no answer within {timeout:g} s")
        return future.result()

    def client(self) -> Any:
        """Return a RosClient over this node, whose age counts from the node's birth."""
        from .client import RosClient

        return RosClient(self.node, self.wait_future, born=self.born)

    def close(self) -> None:
        """Tear down in the order that never aborts the interpreter; idempotent."""
        with contextlib.suppress(Exception):
            self.executor.shutdown(timeout_sec=2.0)
        self._thread.join(timeout=2.0)
        with contextlib.suppress(Exception):
            self.node.destroy_node()
        with contextlib.suppress(Exception):
            self.context.try_shutdown()
