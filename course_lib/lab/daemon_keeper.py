"""The lab's `ros2` daemon, started with the lab's first terminal rather than with the lab.

ros2cli starts its daemon on the first command; a lab that started one with itself paid a
process (about 23 MiB and a DDS participant) for every learner who never opens a terminal.
The lab's terminals ask for it as they open (course_lib/shell/lab_bashrc.bash runs
`python -m course_lib.lab.daemon_keeper`): the machine service starts it as the lab's child,
named and stopped as before, so the learner's first command finds it warm. It then serves the
lab's terminals and journals /parameter_events (course_lib.ros2.command.daemon) until the lab
stops. A command typed before it answers starts one itself, owned by the lab all the same.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Mapping

from ..processes.children import ChildProcess
from ..ros2.node.connect import START_TIMEOUT_S, daemon_argv, daemon_running, start_turn
from ..sim.launcher import Spawner

__all__ = ["DaemonKeeper", "main"]


class DaemonKeeper:
    """Start the lab's daemon once asked (`ensure`); stop it with the lab (`stop`)."""

    def __init__(self, spawn: Spawner, env: Mapping[str, str]) -> None:
        self._spawn = spawn
        self.domain = str(env["ROS_DOMAIN_ID"])
        self._child: ChildProcess | None = None
        self._lock = threading.Lock()

    def ensure(self, timeout: float = START_TIMEOUT_S) -> dict[str, bool]:
        """Start the daemon unless one answers; return {"started": whether this call did}.

        Takes its turn with commands that start or stop one (`start_turn`), so there is never
        a second daemon.
        """
        with self._lock, start_turn(self.domain):
            if daemon_running(self.domain):
                return {"started": False}
            child = self._spawn(daemon_argv(), name=f"ros2-daemon-{self.domain}")
            self._child = child
            deadline = time.monotonic() + timeout
            while not daemon_running(self.domain):
                if not child.alive or time.monotonic() > deadline:
                    raise RuntimeError(
                        f"the lab's ros2 daemon did not start:\n{child.text()[-2000:]}"
                    )
                time.sleep(0.02)
            return {"started": True}

    def stop(self) -> None:
        """Stop the daemon this keeper started, if it still runs."""
        with self._lock:
            if self._child is not None:
                self._child.stop(timeout=5.0)
                self._child = None


def main() -> int:
    """Ask this terminal's lab for its daemon; quietly nothing outside a lab."""
    from ..core.errors import CourseError
    from .client import machine_client

    client = machine_client()
    if client is None:
        return 0
    try:
        client.request("daemon.ensure", timeout=START_TIMEOUT_S + 5.0)
    except CourseError as err:  # the service logged why; a command typed later starts one
        print(err.message, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
