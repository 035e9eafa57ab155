"""Mistakes explained in notebooks, against real nodes: Jazzy's exact text first, then one hint.

The same command lines through the terminal's `ros2` print Jazzy's text and nothing more.
"""

from __future__ import annotations

import os
import textwrap

import pytest
from ros2_golden import (
    GOLDEN,
    console_env,
    daemon,
    golden_cases,
    reset_parameters,
    ros_session,
    run_console,
    start_node,
)

from course_lib.notebook.magics import run_line

__all__ = ["daemon", "ros_session"]  # fixtures of this module

pytestmark = [pytest.mark.ros, pytest.mark.slow]

CASES = golden_cases()
REPO = GOLDEN.parents[2]
NODE = GOLDEN / "nodes" / "param_vel_node.py"
UNDECLARED = CASES["param_set_missing_param"]["stderr"]
INT_FOR_DOUBLE = CASES["param_set_int_literal_on_double"]["stderr"]
NODE_HINT = (
    "Hint: there is no node '/param_vel'; did you mean '/param_vel_node'? "
    "(`%ros2 node list` lists them)\n"
)
PARAM_HINT = (
    "Hint: there is no parameter 'velocty'; did you mean 'velocity'? "
    "(`%ros2 param list /param_vel_node` lists them)\n"
)

# command (without `ros2`), Jazzy's stdout+stderr (from the golden transcripts), the hint line
MISTAKES = {
    "int_for_double": (
        "param set /param_vel_node velocity 1",
        INT_FOR_DOUBLE,
        "Hint: 'velocity' is a double (a number with a decimal point); `1` was read as an "
        "integer and ROS does not convert it: write `1.0`.\n",
    ),
    "text_for_double": (
        "param set /param_vel_node velocity 0,5",
        CASES["param_set_wrong_type"]["stderr"],
        "Hint: 'velocity' is a double (a number with a decimal point); `0,5` was read as text "
        "and ROS does not convert it: write `0.5`.\n",
    ),
    "misspelt_param_set": ("param set /param_vel_node velocty 0.2", UNDECLARED, PARAM_HINT),
    "misspelt_param_get": (
        "param get /param_vel_node velocty",
        CASES["param_get_missing_param"]["stderr"],
        PARAM_HINT,
    ),
    "misspelt_param_describe": ("param describe /param_vel_node velocty", "", PARAM_HINT),
    "misspelt_node_get": (
        "param get /param_vel velocity",
        CASES["param_get_missing_node"]["stderr"],
        NODE_HINT,
    ),
    "misspelt_node_set": (
        "param set /param_vel velocity 0.2",
        CASES["param_set_missing_node"]["stderr"],
        NODE_HINT,
    ),
    "misspelt_node_info": (
        "node info /param_vel",
        CASES["node_info_missing_node"]["stderr"].replace("/no_such_node", "/param_vel"),
        NODE_HINT,
    ),
    "array_not_an_array": (
        "param set /param_types_node gains 1.0",
        "Setting parameter failed: Wrong parameter type, expected 'Type.DOUBLE_ARRAY' got "
        "'Type.DOUBLE'\n",
        "Hint: 'gains' is an array of doubles: write it in brackets and in quotes, as one "
        "argument, e.g. '[1.0, 2.0]'.\n",
    ),
}
SPLIT = "param set /param_types_node gains [1.0, 2.0]"
SPLIT_HINT = (
    "Hint: the value `[1.0, 2.0]` was split at its spaces into 2 arguments: put it in quotes, "
    "as one argument: '[1.0, 2.0]'.\n"
)


@pytest.fixture(scope="module")
def nodes(ros_session):  # type: ignore[no-untyped-def]
    children = [
        start_node(ros_session, "param_vel_node.py", "param_vel_node"),
        start_node(ros_session, "param_types_node.py", "param_types_node"),
    ]
    yield
    reset_parameters({"param_vel_node", "param_types_node"})
    for child in children:
        child.stop()


@pytest.mark.parametrize("case", sorted(MISTAKES))
def test_notebook_shows_jazzy_text_then_the_hint(case: str, nodes) -> None:  # type: ignore[no-untyped-def]
    command, jazzy, hint = MISTAKES[case]
    result = run_line(command)
    assert result.output.text == jazzy  # Jazzy's exact words, untouched
    assert result.text == jazzy + hint
    html = result._repr_html_()
    assert html.index('class="course-hint"') > html.index("ros2 ")
    assert "course-hint" not in html.split('class="course-hint"')[0]


def test_split_array_shows_the_parser_error_then_the_hint(nodes) -> None:  # type: ignore[no-untyped-def]
    result = run_line(SPLIT)
    assert result.output.exit_code == 2
    assert result.output.stderr.endswith("ros2: error: unrecognized arguments: 2.0]\n")
    assert result.text == result.output.text + SPLIT_HINT


def test_right_commands_have_no_hint(nodes) -> None:  # type: ignore[no-untyped-def]
    for command in (
        "param set /param_vel_node velocity 0.0",
        "param set /param_types_node gains '[0.5, 1.0, 2.5]'",
        "param get /param_vel_node velocity",
        "param describe /param_vel_node velocity",
    ):
        result = run_line(command)
        assert result.hints == [] and result.text == result.output.text, command


@pytest.mark.parametrize("case", sorted(MISTAKES))
def test_terminal_prints_jazzy_text_only(case: str, ros_session, nodes, daemon) -> None:  # type: ignore[no-untyped-def]
    command, jazzy, _hint = MISTAKES[case]
    stdout, stderr, _code = run_console(console_env(ros_session), "ros2 " + command)
    assert stdout + stderr == jazzy


def test_terminal_split_array_prints_the_parser_error_only(ros_session, nodes, daemon) -> None:  # type: ignore[no-untyped-def]
    stdout, stderr, code = run_console(console_env(ros_session), "ros2 " + SPLIT)
    assert (stdout, stderr, code) == ("", run_line(SPLIT).output.stderr, 2)
    assert "Hint" not in stderr


def _execute(kc, code: str) -> list[dict]:  # type: ignore[no-untyped-def]
    """Run code in the kernel; return its display/stream/error messages."""
    msg_id = kc.execute(code)
    outputs = []
    while True:
        msg = kc.get_iopub_msg(timeout=60)
        if msg["parent_header"].get("msg_id") != msg_id:
            continue
        kind = msg["msg_type"]
        if kind == "status" and msg["content"]["execution_state"] == "idle":
            return outputs
        if kind in ("display_data", "execute_result", "stream", "error"):
            outputs.append({"type": kind, **msg["content"]})


def test_kernel_display_carries_the_hint_apart() -> None:
    """In a real IPython kernel: the plain text nbval compares, and the HTML line apart."""
    from jupyter_client.manager import start_new_kernel

    env = {**os.environ, "PYTHONPATH": str(REPO)}
    km, kc = start_new_kernel(kernel_name="python3", env=env, cwd=str(REPO))
    try:
        setup = textwrap.dedent(f"""
            %load_ext course_lib.notebook.magics
            import sys
            from course_lib import get_session
            from course_lib.ros2 import client
            _child = get_session().spawn([sys.executable, {str(NODE)!r}], name="vel")
            assert client().wait_for_node("/param_vel_node", include_hidden=False, timeout=10)
            assert client().services_ready("/param_vel_node", timeout=10)
        """)
        assert not [o for o in _execute(kc, setup) if o["type"] == "error"]
        command, jazzy, hint = MISTAKES["int_for_double"]
        (out,) = _execute(kc, f"%ros2 {command}")
        assert out["data"]["text/plain"] == jazzy + hint
        page = out["data"]["text/html"]
        assert page.index("Wrong parameter type") < page.index('<div class="course-hint"')
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=False)


def test_show_hints_false_turns_them_off(nodes, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """An instructor's `show_hints: false` leaves Jazzy's text alone in the notebooks too."""
    from course_lib.lessons import start

    course = (REPO / "config" / "course.yaml").read_text(encoding="utf-8")
    assert "show_hints: true" in course
    settings = tmp_path / "course.yaml"
    settings.write_text(course.replace("show_hints: true", "show_hints: false"), encoding="utf-8")
    command, jazzy, hint = MISTAKES["int_for_double"]
    try:
        start(4, settings_path=str(settings))  # (another lesson's start leaves nodes running)
        assert run_line(command).text == jazzy
        start(5)  # the shipped settings: hints on again
        assert run_line(command).text == jazzy + hint
    finally:
        from course_lib.notebook.hints import set_enabled

        set_enabled(True)
