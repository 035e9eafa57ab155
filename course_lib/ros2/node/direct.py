"""A client node of one process, as ros2cli's DirectNode: `--no-daemon` commands and the daemon.

It has its own rclpy context and a spin thread, no signal handlers and no parameter
services; `use_sim_time` is set as `--use-sim-time` asks. A command's node offers
`~/get_type_description`, the daemon's does not (both as ros2cli's).
"""

from __future__ import annotations

import faulthandler
import os
import sys
from pathlib import Path
from typing import IO, Any

from ...session.session import SpinningNode

__all__ = [
    "CLOSE_LIMIT_S",
    "TEARDOWN_DUMPS_ENV",
    "DirectNode",
    "cli_node_name",
    "daemon_node_name",
]

NODE_NAME_PREFIX = "_ros2cli"
# A command's teardown after its output; then the process ends (exit 1). 5 s was cut short
# once in a suite run: four first calls at once on 2 busy cores, in rclpy's destroy_node.
CLOSE_LIMIT_S = 10.0
# A folder where a teardown cut short leaves its threads' tracebacks (the suite sets it; a
# learner's command writes them nowhere): teardown-<pid>.txt, empty when it ended in time.
TEARDOWN_DUMPS_ENV = "COURSE_TEARDOWN_DUMPS"


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
        self,
        *,
        domain_id: int,
        node_name: str | None = None,
        use_sim_time: bool = False,
        type_description_service: bool = True,
    ) -> None:
        from rclpy.parameter import Parameter

        super().__init__(
            node_name or cli_node_name(),
            domain_id=domain_id,
            owner="the ros2 command's",
            thread_name="ros2cli-spin",
            parameter_overrides=[Parameter("use_sim_time", value=use_sim_time)],
            type_description_service=type_description_service,
        )

    def close_at_exit(self) -> None:
        """Close this node as the process ends, bounded: a teardown that takes more than
        CLOSE_LIMIT_S ends the process with exit code 1, its output already written.

        Fast DDS can spin for ever destroying a participant (seen once: 68 min at 100% of a
        core in destroy_participant -> set_listener; once a 60 s hang of `ros2 topic list
        --no-daemon` in the suite). faulthandler's watchdog is a C thread: it fires even while
        the stuck call holds the GIL. It stays armed through rclpy's own exit handlers, which
        run after this one, and dies with the process when the teardown ends in time.
        """
        sys.stdout.flush()
        sys.stderr.flush()
        faulthandler.dump_traceback_later(CLOSE_LIMIT_S, exit=True, file=_teardown_dump())
        self.close()

    def client(self) -> Any:
        """Return a RosClient over this node, whose age counts from the node's birth."""
        from .client import RosClient

        return RosClient(self.node, self.wait_future, born=self.born)


def _teardown_dump() -> IO[str]:
    """Return the file the teardown's watchdog writes to, kept open to the process's end."""
    folder = os.environ.get(TEARDOWN_DUMPS_ENV)
    if folder:
        try:
            return open(Path(folder) / f"teardown-{os.getpid()}.txt", "w")
        except OSError:
            pass
    return open(os.devnull, "w")
