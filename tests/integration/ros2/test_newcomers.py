"""Which processes a command waits for as nodes starting (`discovery.domain_newcomers`).

A command run moments after a node starts waits until that node has joined (its publishers
and services are then all counted). It must wait only for processes that can join its own
domain: a walled class hub starts each lab in a network namespace of its own and numbers
their domains from 1, so the same ROS_DOMAIN_ID there is another domain (ci112: a hub test
beside a golden one held `ros2 topic bw` for the 6 s cap, three attempts in a row).
"""

from __future__ import annotations

import os
import shutil

import pytest

from course_lib.core.waiting import wait_until
from course_lib.processes.children import spawn
from course_lib.ros2.node.discovery import domain_newcomers

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
