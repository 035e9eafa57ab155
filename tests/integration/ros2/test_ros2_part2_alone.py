"""Part-2 golden cases with the tutorial node running alone, through both doors."""

from __future__ import annotations

import re

import pytest
from ros2_golden import console_env, reset_parameters, run_api, run_console, start_node
from ros2_golden_part2 import (
    CASES,
    SKIPPED,
    compare2,
    interrupt_api,
    interrupt_console,
    names,
)

pytestmark = pytest.mark.ros

BW_LINES = re.compile(
    r"(\d+ B/s from \d+ messages\n\tMessage size mean: 52 B min: 52 B max: 52 B\n)+"
)


@pytest.fixture(scope="module")
def tutorial_node(ros_session):  # type: ignore[no-untyped-def]
    child = start_node(ros_session, "param_vel_node.py", "param_vel_node")
    yield child
    child.stop()


@pytest.fixture(params=["api", "console"])
def door(request, ros_session, tutorial_node, daemon):  # type: ignore[no-untyped-def]
    reset_parameters({"param_vel_node"})
    if request.param == "api":
        return run_api
    env = console_env(ros_session)
    return lambda command: run_console(env, command)


@pytest.mark.parametrize("name", names("alone"))
def test_golden_case_matches(name: str, door) -> None:  # type: ignore[no-untyped-def]
    if name in SKIPPED:
        pytest.skip(SKIPPED[name])
    compare2(CASES[name], door(CASES[name]["command"]))


@pytest.fixture(params=["api", "console"])
def interrupted(request, ros_session, tutorial_node, daemon):  # type: ignore[no-untyped-def]
    if request.param == "api":
        return interrupt_api
    env = console_env(ros_session)
    return lambda command, after_s: interrupt_console(env, command, after_s)


def test_bw_prints_each_second_until_ctrl_c(interrupted) -> None:  # type: ignore[no-untyped-def]
    case = CASES["topic_bw_cmd_vel_5s"]
    stdout, stderr, code = interrupted(case["command"], 3.5)
    assert (stderr, code) == (case["stderr"], case["exit"])
    head, _, rest = stdout.partition("\n")
    assert head == "Subscribed to [/cmd_vel]"
    assert BW_LINES.fullmatch(rest), stdout
    assert BW_LINES.fullmatch(case["stdout"].partition("\n")[2])


def test_hz_waits_for_a_missing_topic_until_ctrl_c(interrupted) -> None:  # type: ignore[no-untyped-def]
    case = CASES["topic_hz_nonexistent"]
    assert interrupted(case["command"], 3.0) == (case["stdout"], case["stderr"], case["exit"])


def test_hz_reports_the_rate_until_ctrl_c(interrupted) -> None:  # type: ignore[no-untyped-def]
    # The real tool's WARNING line is its discovery miss; the course's warm node has none.
    case = CASES["topic_hz_cmd_vel"]
    stdout, stderr, code = interrupted(case["command"], 3.0)
    assert (stderr, code) == (case["stderr"], case["exit"])
    assert re.fullmatch(
        r"(average rate: \d+\.\d{3}\n\tmin: \d\.\d{3}s max: \d\.\d{3}s std dev: \d\.\d{5}s "
        r"window: \d+\n)+",
        stdout,
    ), stdout


def test_service_call_writes_once(door) -> None:  # type: ignore[no-untyped-def]
    from course_lib.ros2.api import nodes_and_params as api

    case = CASES["service_call_set_parameters"]
    compare2(case, door(case["command"]))
    assert api.param_get("/param_vel_node", "velocity").value == 0.2


def test_service_call_waits_for_its_server_until_ctrl_c(interrupted) -> None:  # type: ignore[no-untyped-def]
    out = interrupted("ros2 service call /no_such_service std_srvs/srv/Empty", 2.0)
    assert out == ("waiting for service to become available...\n", "", 2)


def test_topic_pub_at_a_rate_until_ctrl_c(interrupted) -> None:  # type: ignore[no-untyped-def]
    stdout, stderr, code = interrupted(
        "ros2 topic pub -r 5 /chatter std_msgs/msg/String 'data: hi'", 3.0
    )
    assert (stderr, code) == ("", 2)
    head, _, rest = stdout.partition("\n")
    assert head == "publisher: beginning loop"
    published = rest.split("\n\n")
    assert published[-1] == "" and len(published) >= 2, stdout
    assert published[:-1] == [
        f"publishing #{n}: std_msgs.msg.String(data='hi')" for n in range(1, len(published))
    ]


def test_python_api_returns_structured_results(tutorial_node) -> None:  # type: ignore[no-untyped-def]
    import course_lib.ros2 as ros2

    reset_parameters({"param_vel_node"})
    listed = dict(ros2.service_list())
    assert listed["/param_vel_node/get_parameters"] == ["rcl_interfaces/srv/GetParameters"]
    assert ros2.service_type("/param_vel_node/set_parameters") == (
        "rcl_interfaces/srv/SetParameters"
    )
    response = ros2.call_service(
        "/param_vel_node/get_parameters",
        "rcl_interfaces/srv/GetParameters",
        {"names": ["velocity"]},
    )
    assert response.values[0].double_value == 0.0
    assert ros2.topic_info("/cmd_vel") == {
        "types": ["geometry_msgs/msg/Twist"],
        "publishers": 1,
        "subscriptions": 0,
    }
    assert ros2.interface_show("std_srvs/srv/SetBool", comments=False) == (
        "bool data #\n---\nbool success   #\nstring message #\n"
    )
    with pytest.raises(ros2.TopicNotFoundError):
        ros2.service_type("/no_such_service")


def test_service_call_repeats_at_its_rate_until_ctrl_c(interrupted) -> None:  # type: ignore[no-untyped-def]
    stdout, stderr, code = interrupted(
        "ros2 service call /param_vel_node/list_parameters rcl_interfaces/srv/ListParameters -r 5",
        3.0,
    )
    assert (stderr, code) == ("", 2)
    calls = stdout.replace("waiting for service to become available...\n", "")
    request = "requester: making request: rcl_interfaces.srv.ListParameters_Request("
    assert calls.count(request) >= 2 and calls.startswith(request), stdout
    assert calls.count("response:\nrcl_interfaces.srv.ListParameters_Response(") >= 2


def test_topic_pub_from_a_named_node(door) -> None:  # type: ignore[no-untyped-def]
    out = door("ros2 topic pub -n my_publisher --once -w 0 /chatter std_msgs/msg/String 'data: x'")
    assert out == (
        "publisher: beginning loop\npublishing #1: std_msgs.msg.String(data='x')\n\n",
        "",
        0,
    )
