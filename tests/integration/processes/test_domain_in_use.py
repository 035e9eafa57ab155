"""A ROS 2 program that is not the course's, already in a domain, makes the lease skip it."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest
from suite_env import independent_env

from course_lib.processes.domain import domain_in_use, lease_domain

pytestmark = pytest.mark.ros

PLAIN_NODE = """
import sys, rclpy
rclpy.init()
node = rclpy.create_node("someone_elses_node")
print("up", flush=True)
sys.stdin.readline()
"""


@pytest.mark.parametrize("discovery", ["SUBNET", "LOCALHOST"])
def test_a_domain_used_by_a_plain_ros_program_is_skipped(discovery: str) -> None:
    # The probe's lease stays held until the plain program is seen in its domain: released
    # earlier, another test worker could lease that domain, and its session would list
    # someone_elses_node. Once seen, the program itself keeps every lease away.
    probe = lease_domain()
    taken = probe.domain_id
    env = independent_env(ROS_DOMAIN_ID=str(taken), ROS_AUTOMATIC_DISCOVERY_RANGE=discovery)
    other = subprocess.Popen(
        [sys.executable, "-c", PLAIN_NODE],
        env=env,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        try:
            assert other.stdout.readline() == "up\n"
            deadline = time.monotonic() + 5.0
            while not domain_in_use(taken) and time.monotonic() < deadline:
                time.sleep(0.05)
            assert domain_in_use(taken), f"no DDS socket of domain {taken} seen"
        finally:
            probe.release()
        lease = lease_domain({}, start=taken)  # the program holds no course lease
        try:
            assert lease.domain_id != taken
        finally:
            lease.release()
    finally:
        other.communicate("\n", timeout=10)
