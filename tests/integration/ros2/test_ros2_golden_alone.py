"""Golden cases run with the tutorial node alone, through the console command and the API."""

from __future__ import annotations

import pytest
from ros2_golden import (
    compare,
    console_env,
    golden_cases,
    reset_parameters,
    run_api,
    run_console,
    start_node,
)

from course_lib.ros2 import NodeNotFoundError, ParameterNotSetError
from course_lib.ros2.api import nodes_and_params as api

pytestmark = pytest.mark.ros

CASES = golden_cases()
ALONE = sorted(
    name
    for name, case in CASES.items()
    if case["command"].startswith("ros2 ")
    and any("tutorial node running alone" in note for note in case["notes"])
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


@pytest.mark.parametrize("name", ALONE)
def test_golden_case_matches(name: str, door) -> None:  # type: ignore[no-untyped-def]
    case = CASES[name]
    if name == "param_dump_after_set":
        assert door("ros2 param set /param_vel_node velocity 0.2")[2] == 0
    compare(case, door(case["command"]))


def test_api_returns_typed_values(tutorial_node) -> None:  # type: ignore[no-untyped-def]
    reset_parameters({"param_vel_node"})
    assert api.param_get("param_vel_node", "velocity").type_name == "double"
    result = api.param_set("/param_vel_node", "velocity", 1)
    assert not result.successful
    assert result.reason == "Wrong parameter type, expected 'Type.DOUBLE' got 'Type.INTEGER'"
    assert api.param_set("/param_vel_node", "velocity", 0.2).successful
    assert api.param_get("/param_vel_node", "velocity").value == 0.2
    assert api.param_dump("/param_vel_node")["/param_vel_node"]["ros__parameters"] == {
        "start_type_description_service": True,
        "use_sim_time": False,
        "velocity": 0.2,
    }
    assert "/param_vel_node" in api.node_list()
    assert api.topic_echo_once("/cmd_vel").linear.x == 0.2


def test_api_names_missing_node_and_parameter(tutorial_node) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(NodeNotFoundError, match="Node not found: /param_vel_nod"):
        api.param_get("/param_vel_nod", "velocity")
    with pytest.raises(ParameterNotSetError) as info:
        api.param_get("/param_vel_node", "velocty")
    assert "did you mean `velocity`" in str(info.value)
