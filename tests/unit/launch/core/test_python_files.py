"""Python launch files: the shim modules, errors, arguments, params files."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import yaml

from course_lib.launch.command.cli import LaunchCommandError, parse_launch_arguments
from course_lib.launch.command.describe import format_arguments
from course_lib.launch.core.context import LaunchContext
from course_lib.launch.core.description import load_any_launch_file
from course_lib.launch.ros.node import Node
from course_lib.launch.ros.parameters import write_params_file
from course_lib.launch.runtime.process_runner import output_destinations
from course_lib.launch.runtime.service import where_in_launch_file
from course_lib.launch.runtime.shim import MODULE_NAMES, launch_modules

FIXTURE = Path(__file__).resolve().parents[3] / "fixtures" / "launch_pkg" / "launch"


def test_shim_modules_exist_only_inside_the_block() -> None:
    assert not any(name in sys.modules for name in MODULE_NAMES)
    with launch_modules():
        from launch_ros.actions import Node as ShimNode  # type: ignore[import-not-found]

        assert ShimNode is Node
    assert not any(name in sys.modules for name in MODULE_NAMES)


def test_syntax_error_message_is_real_launch_text() -> None:
    with pytest.raises(Exception) as caught:
        load_any_launch_file(str(FIXTURE / "syntax_error.launch.py"))
    assert str(caught.value) == (
        "Caught multiple exceptions when trying to load file of format [py]:\n"
        " - SyntaxError: expected ':' (syntax_error.launch.py, line 4)\n"
        " - InvalidFrontendLaunchFileError: The launch file may have a syntax error, "
        "or its format is unknown"
    )
    assert where_in_launch_file(caught.value) == (str(FIXTURE / "syntax_error.launch.py"), 4)


def test_show_args_text() -> None:
    with launch_modules():
        description = load_any_launch_file(str(FIXTURE / "args.launch.py"))
    assert format_arguments(description) == (
        "Arguments (pass arguments as '<name>:=<value>'):\n\n"
        "    'velocity':\n        Velocity of the robot (m/s)\n        (default: '0.2')\n\n"
        "    'node_name':\n        no description given\n        (default: 'param_vel_node')\n"
    )


def test_launch_arguments_last_wins_and_malformed_rejected() -> None:
    assert parse_launch_arguments(["a:=1", "a:=2", "b:=x:=y"]) == [("a", "2"), ("b", "x:=y")]
    with pytest.raises(LaunchCommandError, match="malformed launch argument 'a='"):
        parse_launch_arguments(["a="])


def test_node_command_line_like_launch_ros() -> None:
    context = LaunchContext()
    node = Node(
        executable="/bin/true",
        name="n",
        namespace="ns",
        parameters=[{"a": {"b": 1}}],
        remappings=[("x", "y")],
        arguments=["--flag"],
    )
    node.execute(context)
    assert node.spec is not None
    assert node.spec.cmd == [
        "/bin/true",
        "--flag",
        "--ros-args",
        "-r",
        "__node:=n",
        "-r",
        "__ns:=/ns",
        "--params-file",
        "<temporary params file>",
        "-r",
        "x:=y",
    ]
    assert node.parameter_sources[0].values == {"a.b": 1}
    assert node.spec.name == "true-1"


def test_params_file_from_dict_uses_wildcard_without_namespace(tmp_path: Path) -> None:
    path = Path(write_params_file("/**", {"velocity": 0.2}))
    try:
        assert path.name.startswith("launch_params_")
        assert yaml.safe_load(path.read_text()) == {"/**": {"ros__parameters": {"velocity": 0.2}}}
    finally:
        path.unlink()


def test_output_aliases() -> None:
    assert output_destinations("log") == {"both": {"log"}, "stdout": set(), "stderr": {"screen"}}
    assert output_destinations("screen")["both"] == {"screen"}
