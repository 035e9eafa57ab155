"""The lab machine service's pure parts: its wire format and reading node names from logs."""

from __future__ import annotations

import pytest

from course_lib.lab.protocol import decode, encode, failure
from course_lib.lab.register import node_name_from_log


def test_messages_round_trip_as_one_line() -> None:
    message = {"op": "node.take", "executable": "param_vel"}
    line = encode(message)
    assert line.endswith(b"\n") and line.count(b"\n") == 1
    assert decode(line) == message


@pytest.mark.parametrize("line", [b"[1, 2]\n", b"not json\n", b'"text"\n'])
def test_anything_but_an_object_is_refused(line: bytes) -> None:
    with pytest.raises(ValueError):
        decode(line)


def test_failure_carries_the_next_step() -> None:
    assert failure("no world", "run lesson.world()") == {
        "ok": False,
        "error": "no world",
        "hint": "run lesson.world()",
    }


@pytest.mark.parametrize(
    ("line", "node"),
    [
        (
            "[INFO] [1795264449.908248855] [param_vel_node]: Velocity parameter is: 0.0",
            "/param_vel_node",
        ),
        (
            "[param_vel-1] [INFO] [1795264449.9] [param_vel_node]: Velocity parameter is",
            "/param_vel_node",
        ),
        ("[WARN] [1.5] [ns.talker]: hello", "/ns/talker"),
        ("[INFO] [launch]: All log files can be found below", ""),
        ("Velocity parameter is: 0.0", ""),
    ],
)
def test_node_name_comes_from_the_log_line(line: str, node: str) -> None:
    assert node_name_from_log(line) == node
