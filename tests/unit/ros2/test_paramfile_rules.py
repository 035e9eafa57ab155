"""rcl's params-file rules, kept in ros2/paramfile.py (pure): which key selects a node (rclpy's
and rclcpp's `/*` -> `(/\\w+)` regex over rcl_yaml_param_parser's node names), how nested keys
make one name, and which `--params-file` arguments rcl reads from a command line."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from course_lib.ros2.paramfile import (
    ParamFileError,
    key_matches,
    node_sections,
    params_files,
    read_param_file,
    ros_arguments,
    sections_for,
)
from course_lib.ros2.values import DOUBLE, INTEGER, ParamValue

NODE = "/param_vel_node"


@pytest.mark.parametrize(
    ("key", "node", "selects"),
    [
        ("/param_vel_node", NODE, True),
        ("param_vel_node", NODE, True),  # rclpy prefixes the slash
        ("/param_vel", NODE, False),
        ("/param_vel_node_2", NODE, False),
        ("/**", NODE, True),
        ("**", NODE, True),
        ("/**", "/ns/deep/param_vel_node", True),
        ("/*", NODE, True),  # one name in the root namespace
        ("*", NODE, True),
        ("/*", "/ns/param_vel_node", False),
        ("/ns/*", "/ns/param_vel_node", True),
        ("/ns/*", "/ns/a/param_vel_node", False),
        ("/ns/**", "/ns/a/param_vel_node", True),
        ("/ns/**", "/ns", True),  # `(/\w+)*` may match nothing
        ("/**/param_vel_node", "/ns/param_vel_node", True),
        ("/**/param_vel_node", NODE, True),
        ("/*/param_vel_node", "/ns/param_vel_node", True),
        ("/*/param_vel_node", NODE, False),
        ("ns/param_vel_node", "/ns/param_vel_node", True),
        ("/ns/param_vel_node", NODE, False),
        ("/param*", NODE, False),  # `*` is a whole name or nothing (rcl refuses `param*`)
        ("/param.vel_node", NODE, False),  # no regex of the learner's dots
    ],
)
def test_key_matches_as_rcl(key: str, node: str, selects: bool) -> None:
    assert key_matches(key, node) is selects


def _sections(text: str) -> list[tuple[str, str, object, bool]]:
    return [(s.name, s.top, s.params, s.has_params) for s in node_sections(yaml.safe_load(text))]


def test_nested_keys_make_one_node_name_as_rcl_joins_them() -> None:
    text = (
        "ns:\n  param_vel_node:\n    ros__parameters: {velocity: 0.1}\n"
        "  other:\n    ros__parameters: {velocity: 0.2}\n"
        "/ns/third:\n  ros__parameters: {velocity: 0.3}\n"
    )
    assert _sections(text) == [
        ("ns/param_vel_node", "ns", {"velocity": 0.1}, True),
        ("ns/other", "ns", {"velocity": 0.2}, True),
        ("/ns/third", "/ns/third", {"velocity": 0.3}, True),
    ]
    data = yaml.safe_load(text)
    assert [s.name for s in sections_for(data, "/ns/param_vel_node")] == ["ns/param_vel_node"]
    assert sections_for(data, NODE) == []


def test_a_key_without_ros_parameters_is_a_section_without_parameters() -> None:
    text = "/param_vel_node:\n  velocity: 0.2\n/empty:\n"
    assert _sections(text) == [
        ("/param_vel_node", "/param_vel_node", None, False),
        ("/empty", "/empty", None, False),
    ]
    assert node_sections([1, 2]) == [] and node_sections(None) == []


def test_a_name_beside_ros_parameters_starts_again_at_the_root_as_in_rcl() -> None:
    # rcl's tracker drops the node's own name at `ros__parameters:`: the sibling is `b`
    text = "/a:\n  ros__parameters: {v: 1}\n  b:\n    ros__parameters: {w: 2}\n"
    assert [s.name for s in node_sections(yaml.safe_load(text))] == ["/a", "b"]


@pytest.mark.parametrize(
    ("argv", "files"),
    [
        (["/x/param_vel", "--ros-args", "--params-file", "a.yaml"], ["a.yaml"]),
        (["/x/param_vel", "--params-file", "a.yaml"], []),  # not a ROS argument
        (["ros2", "run", "p", "e", "--ros-args", "-r", "__node:=n", "--params-file", "a.yaml"],
         ["a.yaml"]),
        (["e", "--ros-args", "--params-file", "a.yaml", "--", "--params-file", "b.yaml"],
         ["a.yaml"]),  # `--` ends the ROS arguments
        (["e", "--ros-args", "-p", "x:=1", "--", "app", "--ros-args", "--params-file", "b.yaml"],
         ["b.yaml"]),  # several blocks
        (["e", "--ros-args", "--ros-args", "--params-file", "a.yaml", "--params-file", "b.yaml"],
         ["a.yaml", "b.yaml"]),
        (["e", "--ros-args", "-p", "--params-file", "--params-file", "a.yaml"], ["a.yaml"]),
        (["e", "--ros-args", "--params-file"], []),  # rcl refuses a trailing flag
    ],
)  # fmt: skip
def test_params_files_as_rcl_reads_its_arguments(argv: list[str], files: list[str]) -> None:
    assert params_files(argv) == files


def test_ros_arguments_pairs_each_flag_with_its_value() -> None:
    argv = ["e", "x", "--ros-args", "-r", "__ns:=/ns", "--log-level", "debug", "-p", "v:=1"]
    assert ros_arguments(argv) == [("-r", "__ns:=/ns"), ("--log-level", "debug"), ("-p", "v:=1")]


def test_a_node_started_with_a_file_takes_its_selecting_sections_in_file_order(
    tmp_path: Path,
) -> None:
    (tmp_path / "p.yaml").write_text(
        "/param_vel_node:\n  ros__parameters: {velocity: 0.2, extra: 1}\n"
        "/*:\n  ros__parameters: {velocity: 0.5}\n"
        "/other:\n  ros__parameters: {velocity: 9.0}\n"
    )
    values = read_param_file("p.yaml", cwd=str(tmp_path), target_node=NODE, at_start=True)
    # rclpy applies rcl's sections in order: `/*` comes later, so it wins
    assert dict(values) == {"velocity": ParamValue(DOUBLE, 0.5), "extra": ParamValue(INTEGER, 1)}
    (tmp_path / "q.yaml").write_text("/*:\n  velocity: 0.5\n")
    with pytest.raises(ParamFileError, match="not a valid ROS parameter file for node /\\*"):
        read_param_file("q.yaml", cwd=str(tmp_path), target_node=NODE, at_start=True)
