"""`ros2 topic echo|bw|hz|delay` as ros2topic 0.32.2 answers, on a scripted graph (issue 67).

The expected texts are transcripts of ros2topic 0.32.2's own verbs run on rclpy 7.1.6 against
publishers of these messages (timestamps and sequence numbers replaced by the scripted info).
"""

from __future__ import annotations

import time
from typing import Any

import pytest
from geometry_msgs.msg import Twist, TwistStamped
from rclpy.serialization import serialize_message
from std_msgs.msg import Byte, MultiArrayDimension, MultiArrayLayout, UInt8MultiArray, UInt32

from course_lib.ros2.command.commands import run_collected
from course_lib.ros2.node.discovery import GraphView
from course_lib.ros2.node.graph_client import GraphClient
from course_lib.ros2.results import TopicInfo

INFO = {
    "source_timestamp": 1,
    "received_timestamp": 2,
    "publication_sequence_number": 3,
    "reception_sequence_number": None,
}
U8 = UInt8MultiArray(
    layout=MultiArrayLayout(dim=[MultiArrayDimension(label="x", size=3, stride=3)], data_offset=1),
    data=[1, 2, 255],
)


class _Node:
    """A client node whose subscriptions receive one scripted message at once."""

    def __init__(self, message: Any) -> None:
        self.message = message

    def create_subscription(self, _type: Any, _topic: str, callback: Any, *_a: Any, **kw: Any):  # type: ignore[no-untyped-def]
        data = serialize_message(self.message) if kw.get("raw") else self.message
        try:
            callback(data, INFO)  # echo's callback takes the message info too
        except TypeError:
            callback(data)
        return object()

    def destroy_subscription(self, _sub: Any) -> None:
        pass

    def get_publishers_info_by_topic(self, _topic: str) -> list:
        return []


class _Graph(GraphClient):
    """A warm client that knows the whole domain: `topics` and nothing else (the topic verbs
    ask a client only about the graph)."""

    def __init__(self, topics: dict[str, str], message: Any = None, *, age: float = 60.0) -> None:
        self._topics = topics  # no rclpy node: the graph is scripted
        self.node = _Node(message)
        self._age = age

    def topics(self, *, include_hidden: bool = False) -> list[TopicInfo]:
        return [TopicInfo(name, (kind,)) for name, kind in self._topics.items()]

    def age(self) -> float:
        return self._age

    def wait_joined(self) -> None:
        pass

    def graph_view(self) -> GraphView:
        return GraphView(frozenset(), frozenset(), missing_participants=0)

    def graph_complete(self) -> bool:
        return True


def _run(argv: list[str], graph: _Graph) -> tuple[str, str, int]:
    out = run_collected(argv, client_factory=lambda: graph)
    return out.stdout, out.stderr, out.exit_code


def test_echo_of_a_topic_a_settled_graph_lacks_answers_at_once() -> None:
    started = time.monotonic()
    got = _run(["topic", "echo", "/no_such_topic", "--once"], _Graph({}))
    took = time.monotonic() - started
    assert got == (
        "WARNING: topic [/no_such_topic] does not appear to be published yet\n",
        "Could not determine the type for the passed topic\n",
        1,
    )
    assert took < 1.0, f"{took:.2f} s: the real tool answers in 0.29-1.12 s"


def test_type_of_a_topic_a_settled_graph_lacks_answers_at_once_when_young() -> None:
    # a `--no-daemon` command's fresh node: the real tool answers after its 0.5 s spin
    started = time.monotonic()
    assert _run(["topic", "type", "/no_such_topic"], _Graph({}, age=1.0)) == ("", "", 1)
    took = time.monotonic() - started
    assert took < 1.0, f"{took:.2f} s (the real tool: 1.7 s with its start)"


@pytest.mark.parametrize("verb", ["bw", "hz", "delay", "echo"])
def test_a_type_this_environment_cannot_import_is_named_invalid(verb: str) -> None:
    graph = _Graph({"/odom": "no_such_msgs/msg/Odometry"})
    assert _run(["topic", verb, "/odom"], graph) == (
        "",
        "The message type 'no_such_msgs/msg/Odometry' is invalid\n",
        1,
    )


@pytest.mark.parametrize(
    ("argv", "message", "stdout"),
    [
        (["--csv", "/u8"], U8, "x,3,3,1,1,2,255\n"),
        (["--csv", "-i", "/byte"], Byte(data=b"\x02"), "1,2,3,None,b'\\x02'\n"),
        (["--csv", "--field", "layout", "/u8"], U8, "x,3,3,1\n"),
        (["--csv", "--field", "layout.data_offset", "/u8"], U8, "1\n---\n"),
        # raw: the serialized bytes (a UInt32 has no padding, whose bytes are left as found)
        (["--raw", "/u32"], UInt32(data=2), "b'\\x00\\x01\\x00\\x00\\x02\\x00\\x00\\x00'\n---\n"),
        (
            ["--raw", "-i", "/u32"],
            UInt32(data=2),
            f"---Got new message, message info:---\n{INFO}\n---Message data:---\n"
            "b'\\x00\\x01\\x00\\x00\\x02\\x00\\x00\\x00'\n---\n",
        ),
        (
            ["-i", "--field", "data", "/byte"],
            Byte(data=b"\x02"),
            f"---Got new message, message info:---\n{INFO}\n---Message data:---\nb'\\x02'\n---\n",
        ),
    ],
)
def test_echo_csv_and_raw_print_as_ros2topic(argv: list[str], message: Any, stdout: str) -> None:
    types = {"/u8": "UInt8MultiArray", "/byte": "Byte", "/u32": "UInt32"}
    graph = _Graph({topic: f"std_msgs/msg/{name}" for topic, name in types.items()}, message)
    assert _run(["topic", "echo", "--once", *argv], graph) == (stdout, "", 0)


def test_echo_of_a_field_a_message_lacks_ends_at_the_first_message() -> None:
    # ros2topic raises in its subscription callback: rclpy's spin passes it on, exit 1
    graph = _Graph({"/u8": "std_msgs/msg/UInt8MultiArray"}, U8)
    assert _run(["topic", "echo", "/u8", "--field", "not_member"], graph) == (
        "",
        "Invalid field 'not_member': 'UInt8MultiArray' object has no attribute 'not_member'\n",
        1,
    )


def test_delay_of_a_message_without_header_ends_at_the_first_message() -> None:
    graph = _Graph({"/cmd_vel": "geometry_msgs/msg/Twist"}, Twist())
    assert _run(["topic", "delay", "/cmd_vel"], graph) == ("", "msg does not have header\n", 1)


def test_delay_window_reports_as_ros2topic() -> None:
    from course_lib.ros2.delay_window import DelayWindow

    window = DelayWindow(size=3)
    assert window.report() is None  # nothing yet: nothing printed
    window.add(10_000_000_000, 9_000_000_000)  # the first message only starts the count
    assert window.report() is None
    for i, delay_ms in enumerate([1, 2, 3, 6]):
        now = 11_000_000_000 + i * 100_000_000
        window.add(now, now - delay_ms * 1_000_000)
    assert window.report() == (
        "average delay: 0.004\n\tmin: 0.002s max: 0.006s std dev: 0.00170s window: 3\n"
    )
    assert window.report() == "no new messages\n"


def test_delay_takes_ros2topics_arguments() -> None:
    stamped = TwistStamped()
    out = run_collected(["topic", "delay", "-h"], client_factory=lambda: _Graph({}, stamped))
    assert out.exit_code == 0
    assert "--window WINDOW, -w WINDOW" in out.stdout
    assert "--spin-time SPIN_TIME" in out.stdout and "-s, --use-sim-time" in out.stdout
