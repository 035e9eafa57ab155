"""Fixtures of the `ros2` integration tests (some defined in ros2_golden.py)."""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator

import pytest
from ros2_golden import console_env, daemon, ros_session, run_console

from course_lib.core.waiting import wait_until
from course_lib.processes.domain import lease_domain
from course_lib.ros2 import start_daemon
from course_lib.ros2.node import connect
from course_lib.session.session import Session, get_session, session_env

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


@pytest.fixture(scope="module")
def lab() -> Iterator[Session]:
    """Yield a session whose kernel-side client and terminal daemon both run (one per module)."""
    session = get_session()
    started = start_daemon(session.env)
    try:
        assert wait_until(lambda: os.path.exists(connect.daemon_socket(session.domain_id)), 15)
        run_console(console_env(session), "ros2 node list")  # the daemon's client is up
        yield session
    finally:
        started.stop()
        session.close()
