"""`ros2 topic pub --once` reaches a subscriber whose process lags behind (a busy machine).

The terminal's `ros2` publishes from the daemon's long-lived node, whose new publisher matches
the known subscription at once: the subscriber's process, not yet run, has not matched it back.
A suite run on 2 busy cores: the docs' one Twist never reached turtlesim (theta stayed 0.0).
Here the subscriber is stopped outright for a second while the command publishes, through
each door that publishes once from a long-lived node: the terminal (the daemon's node), the
notebook's `%ros2` and the lessons' `topic_publish` (the kernel's node).
"""

from __future__ import annotations

import signal
import sys
import threading
from collections.abc import Callable

import pytest
from ros2_golden import run_console

from course_lib.core.waiting import wait_until
from course_lib.notebook.magics import run_line
from course_lib.processes.children import ChildProcess
from course_lib.ros2.api.services_and_topics import topic_publish
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


def _terminal(session: Session, text: str) -> None:
    _out, err, code = run_console(
        session.env, f"ros2 topic pub --once /chatter std_msgs/msg/String '{{data: {text}}}'"
    )
    assert code == 0, err


def _magic(_session: Session, text: str) -> None:
    result = run_line(f"topic pub --once /chatter std_msgs/msg/String '{{data: {text}}}'")
    assert result.output.exit_code == 0, result.output.stderr


def _lessons_api(_session: Session, text: str) -> None:
    topic_publish("/chatter", "std_msgs/msg/String", {"data": text})


def _knows_the_listener(session: Session, door: str) -> bool:
    """Return True once the door's long-lived node knows the one subscription of /chatter."""
    if door == "terminal":
        text = run_console(session.env, "ros2 topic info /chatter")[0]
    else:
        text = run_line("topic info /chatter").output.stdout
    return "Subscription count: 1" in text


DOORS: dict[str, Callable[[Session, str], None]] = {
    "terminal": _terminal,
    "%ros2": _magic,
    "topic_publish": _lessons_api,
}


@pytest.mark.parametrize("door", list(DOORS))
def test_one_message_reaches_a_subscriber_that_lags_while_it_is_published(
    ros_session: Session, daemon: None, door: str
) -> None:
    listener = ros_session.spawn([sys.executable, "-c", LISTENER], name="lagging-listener")
    try:
        _publish_through_lags(ros_session, door, listener)
    finally:  # a failed attempt's listener would make its rerun count two subscriptions (ci93)
        listener.stop()


def _publish_through_lags(session: Session, door: str, listener: ChildProcess) -> None:
    assert listener.wait_for_line("listening", 30), listener.text()
    # the door's long-lived node knows the subscription: its publisher will match it at once
    assert wait_until(lambda: _knows_the_listener(session, door), 20)
    for number in range(ROUNDS):
        listener.send_signal(signal.SIGSTOP, reason="a machine too busy to run it for a while")
        resume = threading.Timer(
            LAG_S, listener.send_signal, (signal.SIGCONT,), {"reason": "it runs again"}
        )
        resume.start()
        try:
            DOORS[door](session, f"round-{number}")
        finally:
            resume.join()
        heard = listener.wait_for_line(f"heard round-{number}$", 10)
        assert heard is not None, f"{door}: round {number} never arrived:\n{listener.text()}"
