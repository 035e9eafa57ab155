"""Part-2 golden cases with the four golden nodes (and a /cmd_vel listener), both doors."""

from __future__ import annotations

import sys
import threading

import pytest
from ros2_golden import GOLDEN, console_env, reset_parameters, run_api, run_console, start_node
from ros2_golden_part2 import CASES, SKIPPED, SUBSCRIBER, compare2, names

from course_lib.core.waiting import wait_until
from course_lib.ros2.api import nodes_and_params as api
from course_lib.ros2.api import services_and_topics as api_more

pytestmark = pytest.mark.ros

NODES = ("param_vel_node", "param_types_node", "guarded_vel_node")
ECHO = "topic_echo_parameter_events_once_with_param_set"
AFTER_SETS = "service_call_get_parameters_after_sets"


@pytest.fixture(scope="module")
def nodes(ros_session):  # type: ignore[no-untyped-def]
    children = [start_node(ros_session, f"{name}.py", name) for name in NODES]
    children.append(
        ros_session.spawn(
            [
                sys.executable,
                str(GOLDEN / "nodes" / "no_param_services_node.py"),
            ],
            name="no_param_services_node",
        )
    )
    children.append(ros_session.spawn([sys.executable, "-c", SUBSCRIBER], name="listener"))
    assert wait_until(lambda: api.client().node.count_subscribers("/cmd_vel") >= 1, 15)
    yield
    for child in children:
        child.stop()


@pytest.fixture(params=["api", "console"])
def door(request, ros_session, nodes, daemon):  # type: ignore[no-untyped-def]
    reset_parameters({"param_vel_node", "param_types_node"})
    if request.param == "api":
        return run_api
    env = console_env(ros_session)
    return lambda command: run_console(env, command)


@pytest.mark.parametrize("name", [n for n in names("four") if n not in (ECHO, AFTER_SETS)])
def test_golden_case_matches(name: str, door) -> None:  # type: ignore[no-untyped-def]
    if name in SKIPPED:
        pytest.skip(SKIPPED[name])
    compare2(CASES[name], door(CASES[name]["command"]))


def test_get_after_sets_matches(door) -> None:  # type: ignore[no-untyped-def]
    for name, value in (("robot_name", "my robot"), ("gains", [1.0, 2.0]), ("count", 9)):
        assert api.param_set("/param_types_node", name, value).successful
    compare2(CASES[AFTER_SETS], door(CASES[AFTER_SETS]["command"]))


def test_echo_once_shows_the_set(door) -> None:  # type: ignore[no-untyped-def]
    got: list[tuple[str, str, int]] = []
    count = api.client().node.count_subscribers
    before = count("/parameter_events")
    runner = threading.Thread(target=lambda: got.append(door(CASES[ECHO]["command"])))
    runner.start()
    assert wait_until(lambda: count("/parameter_events") > before, 15)  # echo subscribed
    # The node's event publisher may match the new subscription a little later: an event
    # sent before that is not received, so the same set is repeated until the echo ends.
    for _ in range(30):
        assert api.param_set("/param_vel_node", "velocity", 0.3).successful
        runner.join(timeout=1.0)
        if not runner.is_alive():
            break
    compare2(CASES[ECHO], got[0])


def test_python_api_publishes_to_a_listener(nodes) -> None:  # type: ignore[no-untyped-def]
    msg = api_more.topic_publish("/cmd_vel", "geometry_msgs/msg/Twist", {"linear": {"x": 0.1}})
    assert msg.linear.x == 0.1
    assert api_more.topic_info("/cmd_vel")["subscriptions"] >= 1
