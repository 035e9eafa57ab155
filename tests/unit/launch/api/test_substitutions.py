"""Substitutions evaluated in a context, without running anything."""

from __future__ import annotations

import shutil

import pytest

from course_lib.launch.api.logic_substitutions import EqualsSubstitution, NotEqualsSubstitution
from course_lib.launch.api.substitutions import (
    Command,
    EnvironmentVariable,
    FindExecutable,
    LaunchConfiguration,
    LocalSubstitution,
    PathJoinSubstitution,
    PythonExpression,
)
from course_lib.launch.core.context import LaunchContext
from course_lib.launch.core.events import Shutdown
from course_lib.launch.core.substitution import (
    SubstitutionFailure,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)
from course_lib.launch.frontend.reader import _cmdline


def _context(**configs: str) -> LaunchContext:
    context = LaunchContext()
    context.launch_configurations.update(configs)
    return context


def _perform(value: object, context: LaunchContext | None = None) -> str:
    context = context or _context()
    return perform_substitutions(context, normalize_to_list_of_substitutions(value))


def test_nested_lists_concatenate_like_a_tutorial_cmd() -> None:
    context = _context(robot_ns="robot1")
    cmd = [FindExecutable(name="sh"), " param set ", LaunchConfiguration("robot_ns"), "/sim"]
    assert _perform([cmd], context) == f"{shutil.which('sh')} param set robot1/sim"


def test_find_executable_missing_names_it() -> None:
    with pytest.raises(SubstitutionFailure, match="executable 'no-such-tool' not found"):
        _perform(FindExecutable(name="no-such-tool"))


def test_command_output_and_failures() -> None:
    assert _perform(Command(["echo ", "hi there"])) == "hi there\n"
    with pytest.raises(SubstitutionFailure, match=r"executed command failed\. Command: false"):
        _perform(Command("false"))
    with pytest.raises(SubstitutionFailure, match="showed stderr output"):
        _perform(Command("sh -c 'echo oops >&2'"))
    assert _perform(Command("sh -c 'echo oops >&2'", on_stderr="ignore")) == ""
    assert _perform(Command("sh -c 'echo oops >&2'", on_stderr="capture")) == "oops\n"


def test_python_expression_has_math_and_launch_configurations() -> None:
    context = _context(v="0.25", use="True")
    expression = PythonExpression([LaunchConfiguration("v"), " == 0.25 and ", "use"])
    with pytest.raises(NameError):
        _perform(expression, context)
    expression = PythonExpression(
        [LaunchConfiguration("v"), " == 0.25 and ", LaunchConfiguration("use")]
    )
    assert _perform(expression, context) == "True"
    assert _perform(PythonExpression("floor(pi)")) == "3"


def test_equals_compares_booleans_and_numbers_loosely() -> None:
    assert _perform(EqualsSubstitution("1", "true")) == "true"
    assert _perform(EqualsSubstitution("0.250", 0.25)) == "true"
    assert _perform(EqualsSubstitution("a", "b")) == "false"
    assert _perform(NotEqualsSubstitution("a", "b")) == "true"


def test_local_substitution_reads_the_event() -> None:
    context = _context()
    context.extend_locals({"event": Shutdown(reason="Node closed")})
    reason = _perform(["asked: ", LocalSubstitution("event.reason")], context)
    assert reason == "asked: Node closed"


def test_launch_configuration_default_and_missing() -> None:
    assert _perform(LaunchConfiguration("x", default="d")) == "d"
    with pytest.raises(SubstitutionFailure, match="launch configuration 'x' does not exist"):
        _perform(LaunchConfiguration("x"))


def test_environment_variable_and_path_join(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COURSE_TEST_USER", "learner")
    context = _context()
    assert _perform([EnvironmentVariable(name="COURSE_TEST_USER"), "_"], context) == "learner_"
    joined = PathJoinSubstitution([("share", "/pkg"), "launch", "x.launch.py"])
    assert _perform(joined) == "share/pkg/launch/x.launch.py"


def test_frontend_command_line_keeps_substitutions_in_their_argument() -> None:
    context = _context(ns="robot3", v="0.25")
    args = _cmdline("ros2 param set $(var ns)/sim velocity $(var v) '{x: 5, y: 2}'")
    assert [perform_substitutions(context, arg) for arg in args] == [
        "ros2",
        "param",
        "set",
        "robot3/sim",
        "velocity",
        "0.25",
        "{x: 5, y: 2}",
    ]


def test_boolean_substitutions_read_launchs_booleans() -> None:
    from course_lib.launch.api.logic_substitutions import (
        AllSubstitution,
        AndSubstitution,
        AnySubstitution,
        IfElseSubstitution,
        NotSubstitution,
        OrSubstitution,
    )

    context = _context(on="True", off="0")
    on, off = LaunchConfiguration("on"), LaunchConfiguration("off")
    assert _perform(NotSubstitution(off), context) == "true"
    assert _perform(AndSubstitution(on, off), context) == "false"
    assert _perform(OrSubstitution(on, off), context) == "true"
    assert _perform(AnySubstitution(off, "false", "1"), context) == "true"
    assert _perform(AllSubstitution(on, "true", off), context) == "false"
    assert _perform(IfElseSubstitution(on, "fast", "slow"), context) == "fast"
    with pytest.raises(SubstitutionFailure, match="Cannot convert value 'maybe' to"):
        _perform(NotSubstitution("maybe"))


def test_frontend_boolean_and_equality_substitutions() -> None:
    from course_lib.launch.api.substitution_syntax import parse_substitution

    context = _context(v="0.25", use="true")
    text = "$(if $(and $(equals $(var v) 0.25) $(var use)) yes no)"
    assert perform_substitutions(context, parse_substitution(text)) == "yes"
    text = "$(not-equals $(var v) 0.250)-$(or false $(not $(var use)))"
    assert perform_substitutions(context, parse_substitution(text)) == "false-false"
