"""A domain's daemons are those of this network: the same number in a network namespace of its
own is another domain (a class hub gives each learner a network of their own, and numbers
their domains from 1, as single-user labs are).

Run 22 of stop 46: the first-call test, listing its leased domain's daemons to kill them, ran
beside the class hub test and counted (then killed) a hub learner's daemon of the same number.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from course_lib.core.waiting import wait_until
from course_lib.hub.guard.wall import enter_own_network, wall_problem
from course_lib.ros2.node import connect

pytestmark = [pytest.mark.ros]


def _start_daemon(env: dict[str, str], *, own_network: bool) -> subprocess.Popen[bytes]:
    return subprocess.Popen(
        [sys.executable, "-m", "course_lib.ros2.command.daemon"],
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        preexec_fn=enter_own_network if own_network else None,
    )


def test_a_daemon_in_another_network_is_not_the_domains(leased_env: dict[str, str]) -> None:
    problem = wall_problem()
    if problem:
        pytest.skip(f"no network namespace here: {problem}")
    domain = leased_env["ROS_DOMAIN_ID"]
    # its own runtime folder too: its socket is not this domain's either
    with tempfile.TemporaryDirectory(dir="/tmp") as elsewhere:
        Path(elsewhere).chmod(0o700)
        other = _start_daemon({**leased_env, "TMPDIR": elsewhere}, own_network=True)
        ours = _start_daemon({**leased_env, "TMPDIR": elsewhere + "-ours"}, own_network=False)
        try:
            assert wait_until(lambda: ours.pid in connect.daemon_pids(domain), 30)
            assert other.poll() is None, "the daemon in its own network ended"
            assert connect.daemon_pids(domain) == [ours.pid]
        finally:
            for daemon in (other, ours):
                daemon.kill()
                daemon.wait()
            shutil.rmtree(elsewhere + "-ours", ignore_errors=True)
