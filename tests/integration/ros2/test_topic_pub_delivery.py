"""`ros2 topic pub --once` reaches a subscriber whose process lags behind (a busy machine).

The terminal's `ros2` publishes from the daemon's long-lived node, whose new publisher matches
the known subscription at once: the subscriber's process, not yet run, has not matched it back.
A suite run on 2 busy cores: the docs' one Twist never reached turtlesim (theta stayed 0.0).
Here the subscriber is stopped outright for a second while the command publishes.
"""

from __future__ import annotations

import signal
import sys
import threading

import pytest
from ros2_golden import run_console

from course_lib.core.waiting import wait_until
from course_lib.session.session import Session

pytestmark = [pytest.mark.ros]

LISTENER = """
import rclpy
from std_msgs.msg import String
rclpy.init()
node = rclpy.create_node("lagging_listener")
node.create_subscription(String, "/chatter", lambda msg: print("heard", msg.data, flush=True), 10)
print("listening", flush=True)
rclpy.spin(node)
"""
LAG_S = 1.0
ROUNDS = 3  # before the change, 1 message in 5 came through a stop of 1 s


def test_one_message_reaches_a_subscriber_that_lags_while_it_is_published(
    ros_session: Session, daemon: None
) -> None:
    listener = ros_session.spawn([sys.executable, "-c", LISTENER], name="lagging-listener")
    assert listener.wait_for_line("listening", 30), listener.text()
    # the daemon's node knows the subscription: its publisher will match it at once
    assert wait_until(
        lambda: (
            "Subscription count: 1" in run_console(ros_session.env, "ros2 topic info /chatter")[0]
        ),
        20,
    )
    for number in range(ROUNDS):
        listener.send_signal(signal.SIGSTOP, reason="a machine too busy to run it for a while")
        resume = threading.Timer(
            LAG_S, listener.send_signal, (signal.SIGCONT,), {"reason": "it runs again"}
        )
        resume.start()
        try:
            _out, err, code = run_console(
                ros_session.env,
                f"ros2 topic pub --once /chatter std_msgs/msg/String '{{data: round-{number}}}'",
            )
        finally:
            resume.join()
        assert code == 0, err
        heard = listener.wait_for_line(f"heard round-{number}$", 10)
        assert heard is not None, f"round {number} never arrived:\n{listener.text()}"
    listener.stop()
