"""`ros2 topic echo --csv|--raw`, `topic delay` and `echo` of a missing topic on live topics,
through both doors, against transcripts of ros2topic 0.32.2 on the same nodes (issue 67)."""

from __future__ import annotations

import re
import sys
import time

import pytest
from ros2_golden import GOLDEN, console_env, reset_parameters, run_api, run_console, start_node
from ros2_golden_part2 import interrupt_api, interrupt_console

from course_lib.core.waiting import wait_until
from course_lib.ros2.api import nodes_and_params as api

pytestmark = pytest.mark.ros

STAMPED = GOLDEN / "nodes" / "stamped_talker.py"  # /stamped, TwistStamped, 10 Hz

# ros2topic's two lines, each second (its test_cli.py's patterns, anchored)
DELAY_LINES = re.compile(
    r"(average delay: \d+\.\d{3}\n\tmin: \d+\.\d{3}s max: \d+\.\d{3}s "
    r"std dev: \d+\.\d{5}s window: \d+\n)+"
)
TWIST_ZERO = "b'\\x00\\x01\\x00\\x00" + "\\x00" * 48 + "'\n---\n"  # 52 B: header + 6 doubles


@pytest.fixture(scope="module")
def nodes(ros_session):  # type: ignore[no-untyped-def]
    children = [
        start_node(ros_session, "param_vel_node.py", "param_vel_node"),
        ros_session.spawn([sys.executable, str(STAMPED)], name="stamped_talker"),
    ]
    assert wait_until(lambda: api.client().node.count_publishers("/stamped") >= 1, 15)
    yield
    for child in children:
        child.stop()


@pytest.fixture(params=["api", "console"])
def door(request, ros_session, nodes, daemon):  # type: ignore[no-untyped-def]
    reset_parameters({"param_vel_node"})
    if request.param == "api":
        return run_api
    env = console_env(ros_session)
    return lambda command: run_console(env, command)


@pytest.fixture(params=["api", "console"])
def interrupted(request, ros_session, nodes, daemon):  # type: ignore[no-untyped-def]
    if request.param == "api":
        return interrupt_api
    env = console_env(ros_session)
    return lambda command, after_s: interrupt_console(env, command, after_s)


def test_echo_csv_prints_one_line_per_message(door) -> None:  # type: ignore[no-untyped-def]
    assert door("ros2 topic echo --csv --once /cmd_vel") == ("0.0,0.0,0.0,0.0,0.0,0.0\n", "", 0)


def test_echo_raw_prints_the_serialized_bytes(door) -> None:  # type: ignore[no-untyped-def]
    assert door("ros2 topic echo --raw --once /cmd_vel") == (TWIST_ZERO, "", 0)


def test_delay_prints_each_second_until_ctrl_c(interrupted) -> None:  # type: ignore[no-untyped-def]
    stdout, stderr, code = interrupted("ros2 topic delay /stamped", 2.5)
    assert (stderr, code) == ("", 2)
    assert DELAY_LINES.fullmatch(stdout), stdout
    assert float(stdout.split()[2]) < 0.5  # the stamps are taken as each message is sent


def test_delay_window(interrupted) -> None:  # type: ignore[no-untyped-def]
    stdout, _stderr, _code = interrupted("ros2 topic delay -w 3 /stamped", 2.5)
    assert DELAY_LINES.fullmatch(stdout), stdout
    assert set(re.findall(r"window: (\d+)", stdout)) == {"3"}


def test_delay_of_a_type_without_header(door) -> None:  # type: ignore[no-untyped-def]
    assert door("ros2 topic delay /cmd_vel") == ("", "msg does not have header\n", 1)


def test_echo_of_a_missing_topic_answers_once_the_graph_is_settled(nodes) -> None:  # type: ignore[no-untyped-def]
    # in-process: a terminal's Python adds its own start (seconds on a loaded host)
    assert wait_until(api.client().graph_complete, 15)  # the client knows the whole domain
    started = time.monotonic()
    got = run_api("ros2 topic echo /no_such_topic")
    took = time.monotonic() - started
    assert got == (
        "WARNING: topic [/no_such_topic] does not appear to be published yet\n",
        "Could not determine the type for the passed topic\n",
        1,
    )
    assert took < 1.12, f"{took:.2f} s (the real tool: 0.29-1.12 s)"
