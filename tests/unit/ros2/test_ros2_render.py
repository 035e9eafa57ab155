"""Every golden text the renderers produce, from data, byte for byte (no ROS)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from course_lib.ros2 import render
from course_lib.ros2.paramfile import ParamFileError, read_param_file
from course_lib.ros2.results import (
    Descriptor,
    NodeInfo,
    ParamListing,
    ParamRange,
    SetResult,
    TopicInfo,
    node_name_of,
)
from course_lib.ros2.values import BOOL, DOUBLE, STRING, ParamValue

GOLDEN = Path(__file__).resolve().parents[2] / "golden" / "ros2"
CASES = {c["case"]: c for c in json.loads((GOLDEN / "cases.json").read_text())}
VEL_NAMES = ("velocity", "use_sim_time", "start_type_description_service")
TYPES_NAMES = (
    "count",
    "flags",
    "frame_id",
    "gains",
    "max_speed",
    "names",
    "pid.ki",
    "pid.kp",
    "retries",
    "robot_name",
    "start_type_description_service",
    "use_sim_time",
)
TYPES_VALUES = {
    "count": 5,
    "flags": [True, False, True],
    "frame_id": "base_link",
    "gains": [0.5, 1.0, 2.5],
    "max_speed": 1.0,
    "names": ["left", "right"],
    "pid.ki": 0.1,
    "pid.kp": 1.0,
    "retries": 3,
    "robot_name": "turtle",
    "start_type_description_service": True,
    "use_sim_time": False,
}


def assert_golden(name: str, output) -> None:  # type: ignore[no-untyped-def]
    case = CASES[name]
    assert (output.stdout, output.stderr, output.exit_code) == (
        case["stdout"],
        case["stderr"],
        case["exit"],
    )


def _vel() -> ParamListing:
    return ParamListing(
        node_name_of("/param_vel_node"),
        VEL_NAMES,
        {"velocity": DOUBLE, "use_sim_time": BOOL, "start_type_description_service": BOOL},
    )


def test_param_list_texts() -> None:
    types = ParamListing(node_name_of("/param_types_node"), TYPES_NAMES)
    assert_golden("param_list_node", render.param_list([_vel()], single_node=True))
    assert_golden("param_list_single_node_running", render.param_list([_vel()], single_node=False))
    assert_golden(
        "param_list_all_two_nodes", render.param_list([_vel(), types], single_node=False)
    )
    assert_golden(
        "param_list_node_param_type",
        render.param_list([_vel()], single_node=True, with_types=True),
    )


@pytest.mark.parametrize(
    ("name", "value", "hide"),
    [
        ("param_get_velocity", ParamValue(DOUBLE, 0.0), False),
        ("param_get_velocity_hide_type", ParamValue(DOUBLE, 0.0), True),
        ("param_get_use_sim_time", ParamValue(BOOL, False), False),
        ("param_get_int", ParamValue.of(5), False),
        ("param_get_string", ParamValue(STRING, "turtle"), False),
        ("param_get_double_array", ParamValue.of([0.5, 1.0, 2.5]), False),
        ("param_get_missing_param", None, False),
    ],
)
def test_param_get_texts(name: str, value: ParamValue | None, hide: bool) -> None:
    assert_golden(name, render.param_get(value, hide_type=hide))


@pytest.mark.parametrize(
    ("name", "result"),
    [
        ("param_set_success", SetResult(True)),
        (
            "param_set_wrong_type",
            SetResult(False, "Wrong parameter type, expected 'Type.DOUBLE' got 'Type.STRING'"),
        ),
        (
            "param_set_read_only",
            SetResult(False, "Trying to set a read-only parameter: frame_id."),
        ),
        ("param_set_rejected_by_callback", SetResult(False, "velocity must be >= 0.0")),
        (
            "param_set_missing_param",
            SetResult(False, "Invalid access to undeclared parameter(s): []"),
        ),
    ],
)
def test_param_set_texts(name: str, result: SetResult) -> None:
    assert_golden(name, render.param_set(result))


def test_param_delete_and_missing_node_texts() -> None:
    assert_golden(
        "param_delete_declared",
        render.param_delete(SetResult(False, "Static parameter cannot be undeclared")),
    )
    for name in (
        "param_get_missing_node",
        "param_set_missing_node",
        "param_dump_missing_node",
        "param_describe_missing_node",
        "param_list_missing_node",
    ):
        assert_golden(name, render.failure("Node not found"))
    assert_golden("node_info_missing_node", render.failure("Unable to find node '/no_such_node'"))


def test_param_describe_texts() -> None:
    assert_golden(
        "param_describe_velocity",
        render.param_describe(
            [Descriptor("velocity", DOUBLE, "Sets the velocity (in m/s) of the robot.")]
        ),
    )
    assert_golden(
        "param_describe_float_range",
        render.param_describe(
            [
                Descriptor(
                    "max_speed",
                    DOUBLE,
                    "Maximum speed in m/s.",
                    ranges=(ParamRange(0.0, 2.0, 0.0),),
                )
            ]
        ),
    )
    assert_golden(
        "param_describe_read_only",
        render.param_describe(
            [Descriptor("frame_id", STRING, "Frame of the robot base.", read_only=True)]
        ),
    )


def test_param_dump_texts() -> None:
    vel = [
        ("start_type_description_service", ParamValue.of(True)),
        ("use_sim_time", ParamValue.of(False)),
        ("velocity", ParamValue.of(0.0)),
    ]
    assert_golden("param_dump", render.param_dump("/param_vel_node", vel))
    types = [(k, ParamValue.of(v)) for k, v in sorted(TYPES_VALUES.items())]
    assert_golden("param_dump_types_node", render.param_dump("/param_types_node", types))


def test_param_load_texts() -> None:
    values = read_param_file("params/types_node_dump.yaml", cwd=str(GOLDEN))
    refused = {"frame_id", "start_type_description_service"}
    results = [
        SetResult(
            name not in refused,
            f"Trying to set a read-only parameter: {name}." if name in refused else "",
            name,
        )
        for name, _ in values
    ]
    assert_golden("param_load_dumped_file", render.param_load(results))


def test_graph_texts() -> None:
    topics = [
        TopicInfo("/cmd_vel", ("geometry_msgs/msg/Twist",)),
        TopicInfo("/parameter_events", ("rcl_interfaces/msg/ParameterEvent",)),
        TopicInfo("/rosout", ("rcl_interfaces/msg/Log",)),
    ]
    assert_golden("topic_list", render.topic_list(topics))
    assert_golden("topic_list_t", render.topic_list(topics, show_types=True))
    assert_golden("node_list", render.node_list(["/param_vel_node"]))
    srv = [
        (f"/param_vel_node/{s}", f"{p}/srv/{t}")
        for s, p, t in [
            ("describe_parameters", "rcl_interfaces", "DescribeParameters"),
            ("get_parameter_types", "rcl_interfaces", "GetParameterTypes"),
            ("get_parameters", "rcl_interfaces", "GetParameters"),
            ("get_type_description", "type_description_interfaces", "GetTypeDescription"),
            ("list_parameters", "rcl_interfaces", "ListParameters"),
            ("set_parameters", "rcl_interfaces", "SetParameters"),
            ("set_parameters_atomically", "rcl_interfaces", "SetParametersAtomically"),
        ]
    ]
    info = NodeInfo(
        "/param_vel_node",
        publishers=tuple(topics),
        service_servers=tuple(TopicInfo(n, (t,)) for n, t in srv),
    )
    assert_golden("node_info", render.node_info(info))


def test_param_file_values_go_through_yaml_again() -> None:
    assert read_param_file("params/vel_int.yaml", cwd=str(GOLDEN)) == [
        ("velocity", ParamValue.of(1))
    ]
    assert read_param_file("params/vel_wildcard.yaml", cwd=str(GOLDEN)) == [
        ("velocity", ParamValue.of(0.35))
    ]
    with pytest.raises(ParamFileError) as info:
        read_param_file("params/vel_malformed.yaml", cwd=str(GOLDEN))
    assert info.value.output.exit_code == 1
    assert info.value.output.stderr.startswith("Traceback (most recent call last):\n")
    assert 'in "params/vel_malformed.yaml", line 3, column 15' in info.value.output.stderr
