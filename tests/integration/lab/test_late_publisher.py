"""A node whose /cmd_vel publisher comes late in its constructor is still found driving.

`one_driver` stops the lessons' other drivers when a new node drives. It decided too early
that lesson 11's descriptor_vel does not drive: its /rosout was seen before its constructor
had made its /cmd_vel publisher (a busy host, the CI's full walk), so lesson 7's node kept
driving and lesson 11's check was "not judged". Here the node sleeps in between, on purpose.
"""

from __future__ import annotations

import sys

import pytest

from course_lib.lab.drivers import _drives
from course_lib.processes.children import spawn
from course_lib.ros2.node.client import RosClient
from course_lib.session.session import Session

pytestmark = pytest.mark.ros

LATE_DRIVER = """
import time, rclpy
from geometry_msgs.msg import Twist
rclpy.init()
node = rclpy.create_node("late_driver")
print("rosout", flush=True)
time.sleep(1.5)  # a constructor that declares parameters before its publisher, on a busy host
node.create_publisher(Twist, "cmd_vel", 10)
rclpy.spin(node)
"""
NON_DRIVER = """
import rclpy
rclpy.init()
node = rclpy.create_node("watcher")
print("rosout", flush=True)
rclpy.spin(node)
"""


@pytest.mark.parametrize(("script", "drives"), [(LATE_DRIVER, True), (NON_DRIVER, False)])
def test_a_new_node_is_judged_once_its_constructor_is_done(
    session: Session, script: str, drives: bool
) -> None:
    client = RosClient(session.node, session.wait_future)
    child = spawn([sys.executable, "-c", script], name="node", env=session.env)
    try:
        assert child.wait_for_line("rosout", 30), child.text()
        assert _drives(client, child.pid) is drives
    finally:
        child.stop()
