"""The `ros2` daemon stops cleanly on SIGINT (Ctrl-C), even when started with SIGINT ignored."""

from __future__ import annotations

import os
import signal

import pytest

from course_lib.core.waiting import wait_until
from course_lib.processes.children import spawn
from course_lib.ros2.node.connect import daemon_argv, daemon_socket
from course_lib.session.session import Session

pytestmark = pytest.mark.ros


@pytest.mark.parametrize("ignored", [False, True], ids=["plain", "started-with-sigint-ignored"])
def test_daemon_exits_cleanly_on_sigint(session: Session, ignored: bool) -> None:
    # A shell's background job (`ros2 daemon &`) starts with SIGINT ignored.
    argv = (
        ["sh", "-c", 'trap "" INT; exec "$@"', "sh", *daemon_argv()] if ignored else daemon_argv()
    )
    child = spawn(argv, name="ros2-daemon", env=session.env)
    path = daemon_socket(session.domain_id)
    try:
        assert wait_until(lambda: os.path.exists(path), 15), "the daemon never listened"
        os.kill(child.pid, signal.SIGINT)  # the daemon alone, not its process group
        assert child.wait(timeout=5) == 0, "the daemon ignored SIGINT or died of it"
        assert not os.path.exists(path)
    finally:
        child.stop()
