"""Which processes a command waits for as nodes starting (`participants.domain_newcomers`).

A command run moments after a node starts waits until that node has joined (its publishers
and services are then all counted). It must wait only for processes that can join its own
domain: a walled class hub starts each lab in a network namespace of its own and numbers
their domains from 1, so the same ROS_DOMAIN_ID there is another domain (ci112: a hub test
beside a golden one held `ros2 topic bw` for the 6 s cap, three attempts in a row).
"""

from __future__ import annotations

import os
import shutil
import sys
import time

import pytest

from course_lib.core.host import procfs
from course_lib.core.waiting import wait_until
from course_lib.processes.children import spawn
from course_lib.ros2.node.participants import NEWCOMER_S, UNJOINED_S, domain_newcomers

pytestmark = pytest.mark.ros

# Outside the domains the course leases (processes/domain.py): no session of the suite uses
# it, so this test's processes hold no other test's command.
DOMAIN = "150"


def test_a_process_of_the_same_domain_number_in_another_network_is_no_newcomer() -> None:
    unshare = shutil.which("unshare")
    if unshare is None or os.geteuid() != 0:
        pytest.skip("needs root and `unshare` for a network namespace (the CI runs as root)")
    env = {**os.environ, "ROS_DOMAIN_ID": DOMAIN}
    here = spawn(["sleep", "30"], name="same network", env=env)
    walled = spawn([unshare, "--net", "sleep", "30"], name="own network", env=env)
    try:
        assert wait_until(lambda: here.pid in domain_newcomers(int(DOMAIN), joined=True), 5)
        # `unshare` execs sleep in the new network once it has made it
        assert wait_until(lambda: os.readlink(f"/proc/{walled.pid}/exe").endswith("sleep"), 5)
        newcomers = domain_newcomers(int(DOMAIN), joined=True)
        assert here.pid in newcomers
        assert walled.pid not in newcomers
    finally:
        here.stop()
        walled.stop()


def test_a_process_that_never_loads_ros_stops_being_a_newcomer_after_unjoined_s() -> None:
    """A kernel opened beside a running lesson (it joins only at its lesson's first cell) or a
    plain script holds a command for UNJOINED_S, not NEWCOMER_S (it held every lookup of the
    lab until it was 6 s old); a process importing rclpy on a busy host is still waited for."""
    env = {**os.environ, "ROS_DOMAIN_ID": DOMAIN}
    plain = spawn(["sleep", "30"], name="a plain program", env=env)
    importing = spawn(
        [sys.executable, "-c", "import rclpy, time; time.sleep(30)"], name="no node yet", env=env
    )
    started = time.monotonic()
    try:
        assert wait_until(lambda: procfs.maps_library(importing.pid, "librcl.so"), 5)
        time.sleep(max(0.0, started + UNJOINED_S + 0.5 - time.monotonic()))
        newcomers = domain_newcomers(int(DOMAIN), joined=True)
        assert plain.pid not in newcomers
        assert importing.pid in newcomers, "a process that loaded ROS may still start a node"
        assert UNJOINED_S + 0.5 < NEWCOMER_S
    finally:
        plain.stop()
        importing.stop()
