"""Golden cases run with the tutorial node and the typed-parameters node (and the guarded one)."""

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

from course_lib.ros2.api import nodes_and_params as api

pytestmark = pytest.mark.ros

CASES = golden_cases()
TWO_NODES = sorted(
    name
    for name, case in CASES.items()
    if case["command"].startswith("ros2 ")
    and any("/param_types_node (" in note for note in case["notes"])
)
GUARDED = "param_set_rejected_by_callback"


@pytest.fixture(scope="module")
def nodes(ros_session):  # type: ignore[no-untyped-def]
    children = [
        start_node(ros_session, "param_vel_node.py", "param_vel_node"),
        start_node(ros_session, "param_types_node.py", "param_types_node"),
    ]
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


@pytest.mark.parametrize("name", TWO_NODES)
def test_golden_case_matches(name: str, door) -> None:  # type: ignore[no-untyped-def]
    compare(CASES[name], door(CASES[name]["command"]))


def test_callback_rejection_matches(ros_session, nodes, door) -> None:  # type: ignore[no-untyped-def]
    guarded = start_node(ros_session, "guarded_vel_node.py", "guarded_vel_node")
    try:
        compare(CASES[GUARDED], door(CASES[GUARDED]["command"]))
    finally:
        guarded.stop()


def test_bad_param_file_changes_nothing(nodes) -> None:  # type: ignore[no-untyped-def]
    reset_parameters({"param_vel_node"})
    out = run_api("ros2 param load /param_vel_node params/vel_malformed.yaml")
    assert out[2] == 1
    assert 'in "params/vel_malformed.yaml", line 3, column 15' in out[1]
    assert api.param_get("/param_vel_node", "velocity").value == 0.0
    out = run_api("ros2 param load /param_vel_node params/vel_missing_ros_parameters.yaml")
    assert out == ("", "YAML file is not a valid ROS parameter file for node /param_vel_node\n", 1)


def test_load_applies_other_sections_and_wildcard(nodes) -> None:  # type: ignore[no-untyped-def]
    reset_parameters({"param_vel_node"})
    assert run_api("ros2 param load /param_vel_node params/vel_both.yaml")[0] == (
        "Set parameter velocity successful\n"
    )
    assert api.param_get("/param_vel_node", "velocity").value == 0.7
    out = run_api("ros2 param load /param_vel_node params/vel_wildcard.yaml --no-use-wildcard")
    assert out == ("", "Param file does not contain selected parameters\n", 1)
