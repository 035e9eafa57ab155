"""Fixtures of the `ros2` integration tests (some defined in ros2_golden.py)."""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator

import pytest
from ros2_golden import daemon, ros_session

from course_lib.processes.domain import lease_domain
from course_lib.ros2.node import connect
from course_lib.session.session import session_env

__all__ = ["daemon", "leased_env", "ros_session"]


@pytest.fixture
def leased_env() -> Iterator[dict[str, str]]:
    """Yield a session's environment in a domain leased for one test; the daemons it started
    there are stopped afterwards (killed if they do not stop)."""
    lease = lease_domain({})
    try:
        yield session_env(lease.domain_id)
    finally:
        connect.stop_daemon(lease.domain_id)
        for pid in connect.daemon_pids(lease.domain_id):
            os.kill(pid, signal.SIGKILL)
        lease.release()
