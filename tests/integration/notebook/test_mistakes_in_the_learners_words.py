"""Issue 59 through the notebook's `%ros2`, against the real nodes of the course workspace:
Jazzy's exact text first, then one hint that names the real cause with the learner's numbers.

A velocity the robot cannot reach, a unit after the value, a wrong executable or package, and
a node another lesson stopped (the lab's one-driver rule) when the learner comes back to it.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from ros2_golden import golden_cases

from course_lib.core import ament
from course_lib.core.errors import PackageNotFoundError
from course_lib.lab.takeover import set_label
from course_lib.notebook.magics import run_line
from course_lib.session.session import Session, get_session

pytestmark = [pytest.mark.ros, pytest.mark.slow]

CASES = golden_cases()
WRONG_TYPE = CASES["param_set_wrong_type"]["stderr"]  # Jazzy: expected DOUBLE got STRING
STOPPED_LINE = (
    "Stopped /param_vel_node (param_vel) that lesson 7 had started: one node at a time drives "
    "your lab's robot."
)


def _has_workspace() -> bool:
    try:
        env = ament.workspace_env()
        return "param_vel" in ament.package_executables("parameter_tests", env)
    except PackageNotFoundError:
        return False


if not _has_workspace():
    pytest.skip("rosject not built", allow_module_level=True)


@pytest.fixture(scope="module")
def session() -> Iterator[Session]:
    course_session = get_session()
    yield course_session
    set_label("this notebook")
    course_session.close()


@pytest.fixture
def param_vel(session: Session) -> Iterator[None]:
    started = run_line("run parameter_tests param_vel")
    assert "Velocity parameter is: 0.000000" in started.output.text, started.text
    yield
    for child in session.children:
        child.stop()


def test_a_velocity_past_top_speed_is_set_then_explained(param_vel: None) -> None:
    result = run_line("param set /param_vel_node velocity 5.0")
    assert result.output.text == CASES["param_set_success"]["stdout"]  # Jazzy's words, untouched
    assert result.hints == [
        "/param_vel_node now holds velocity 5.0 (its velocity has no range), but the robot "
        "tops out at 0.26 m/s: it drives forwards at 0.26 m/s."
    ]
    reachable = run_line("param set /param_vel_node velocity 0.2")
    assert reachable.hints == [] and reachable.text == CASES["param_set_success"]["stdout"]


def test_a_unit_after_the_value_is_not_sent_round_the_quotes(param_vel: None) -> None:
    split = run_line("param set /param_vel_node velocity 0.15 m/s")
    assert split.output.exit_code == 2
    assert split.output.stderr.endswith("ros2: error: unrecognized arguments: m/s\n")
    assert split.hints == [
        "parameters carry no unit: `%ros2 param set /param_vel_node velocity 0.15` (velocity "
        "is in m/s)."
    ]
    quoted = run_line("param set /param_vel_node velocity '0.15 m/s'")  # as the quotes hint said
    assert quoted.output.text == WRONG_TYPE
    assert quoted.hints == [
        "'velocity' is a double (a number with a decimal point); `0.15 m/s` was read as text "
        "and ROS does not convert it: write `0.15` (parameters carry no unit; velocity is in "
        "m/s)."
    ]
    assert run_line("param set /param_vel_node velocity 0.15").hints == []  # the hint's command


def test_a_wrong_executable_or_package_names_the_closest(session: Session) -> None:
    wrong_executable = run_line("run parameter_tests param_velocity")
    assert wrong_executable.output.text == CASES["run_missing_executable"]["stderr"]
    assert wrong_executable.hints == [
        "package 'parameter_tests' has no executable 'param_velocity'; did you mean "
        "'param_vel'? `%ros2 run parameter_tests param_vel`."
    ]
    wrong_package = run_line("run parameter_test param_vel")
    assert wrong_package.output.text == "Package 'parameter_test' not found\n"
    assert wrong_package.hints == [
        "there is no package 'parameter_test'; did you mean 'parameter_tests'? "
        "`%ros2 run parameter_tests param_vel`."
    ]
    assert not session.children  # nothing started


def test_a_node_another_lesson_stopped_names_that_lesson_and_the_cell(
    session: Session, capsys: pytest.CaptureFixture[str]
) -> None:
    set_label("lesson 7")
    try:
        assert "Velocity parameter is" in run_line("run parameter_tests param_vel").text
        set_label("lesson 11")
        run_line("run parameter_descriptors descriptor_vel")
        assert STOPPED_LINE in capsys.readouterr().out  # the one-driver rule, as before
        set_label("lesson 7")  # the learner goes back to lesson 7's notebook
        result = run_line("param set /param_vel_node velocity 0.1")
        assert result.output.text == CASES["param_set_missing_node"]["stderr"]  # Node not found
        assert result.hints == [
            "/param_vel_node is not running: lesson 11 stopped it when it started "
            "/descriptor_vel_node (one node at a time drives your lab's robot). To use it here, "
            "start it again with `%ros2 run parameter_tests param_vel` (that stops "
            "/descriptor_vel_node in turn)."
        ]
        run_line("run parameter_tests param_vel")  # the hint's cell
        again = run_line("param set /param_vel_node velocity 0.1")
        assert again.hints == [] and again.text == CASES["param_set_success"]["stdout"]
    finally:
        for child in session.children:
            child.stop()


def test_a_node_that_ran_here_before_is_named_with_the_command_that_started_it(
    session: Session,
) -> None:
    """Stopped by a kernel restart, `lesson.stop` or Ctrl-C (no lesson took it over): the
    hint gives the `%ros2 run` line that started it in this lab, its --ros-args too."""
    started = run_line("run parameter_tests param_vel --ros-args -p velocity:=0.1")
    assert "Velocity parameter is: 0.100000" in started.output.text, started.text
    for child in session.children:
        child.stop()
    gone = run_line("param get /param_vel_node velocity")
    assert gone.output.stderr.startswith("Node not found"), gone.text
    assert gone.hints == [
        "/param_vel_node is not running now (it ran in this lab before): start it again: "
        "`%ros2 run parameter_tests param_vel --ros-args -p velocity:=0.1`."
    ], gone.hints
