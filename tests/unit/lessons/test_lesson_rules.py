"""Pure parts of the lessons: settings validation, self-check text, the exercise judge, files."""

from __future__ import annotations

import shlex
from pathlib import Path

import pytest
import yaml

from course_lib.config.loader import parse_settings
from course_lib.config.trip import Trip
from course_lib.core.errors import ConfigError
from course_lib.lessons.files import atomic_write, diff_text, numbered
from course_lib.lessons.judging import TravelAttempt, judge_travel
from course_lib.lessons.report import SelfCheck, check
from course_lib.lessons.settings import CourseSettings, course_yaml, load_course_settings
from course_lib.notebook.widgets.yaml_file import params_yaml, set_command, write_params_file

ANSWER = Trip(5.0, 0.2)


def test_the_shipped_course_yaml_is_valid() -> None:
    assert isinstance(load_course_settings(course_yaml()), CourseSettings)


@pytest.mark.parametrize(
    ("text", "line", "key", "words"),
    [
        ("default_velocity_mps: 0.5\n", 1, "default_velocity_mps", "out of range"),
        ("show_hint: true\n", 1, "show_hint", "unknown key"),
        ("show_hints: maybe\n", 1, "show_hints", "expected true or false"),
        ("travel_exercise:\n  target_m: 1.0\n  tolerance_m: fast\n", 3, "tolerance_m", "number"),
        ("travel_exercise:\n  target_m: 0.4\n  tolerance_m: 0.2\n", 3, "tolerance_m", "quarter"),
    ],
)
def test_settings_errors_name_file_line_and_key(
    text: str, line: int, key: str, words: str
) -> None:
    with pytest.raises(ConfigError) as err:
        parse_settings(text, CourseSettings, source="config/course.yaml")
    assert err.value.path == "config/course.yaml"
    assert err.value.line == line
    assert err.value.key.endswith(key)
    assert words in str(err.value)


def test_unknown_key_suggests_the_closest() -> None:
    with pytest.raises(ConfigError, match="did you mean `show_hints`"):
        parse_settings("show_hint: true\n", CourseSettings, source="config/course.yaml")


def test_self_check_says_what_to_try_only_for_failures() -> None:
    report = SelfCheck.of(7, [check("drove", True, "x"), check("stopped", False, "set 0.0")])
    assert report.text() == (
        "Self-check, lesson 7\n  ✓ passed: drove\n  ✗ not yet: stopped\n      Try: set 0.0\n"
        "1 of 2 checks passed: fix what is not yet passed above, then run this cell again.\n"
    )
    assert not report.passed


@pytest.mark.parametrize(
    ("attempt", "passed", "words"),
    [
        (TravelAttempt(True, True, 0.99), True, "passed"),
        (TravelAttempt(True, True, 1.049), True, "passed"),
        (TravelAttempt(True, True, 0.40), False, "0.60 m short of"),
        (TravelAttempt(True, True, 1.20), False, "0.20 m past"),
        (TravelAttempt(False, False, 0.0), False, "did not move"),
        (TravelAttempt(True, False, 1.3), False, "still moving"),
    ],
)
def test_travel_judge(attempt: TravelAttempt, passed: bool, words: str) -> None:
    verdict = judge_travel(
        attempt, target_m=1.0, tolerance_m=0.05, number=1, show_hints=True, answer=ANSWER
    )
    assert verdict.passed is passed
    assert words in verdict.message
    assert bool(verdict.hint) is (not passed)


def test_hints_follow_attempts_and_can_be_off() -> None:
    miss = TravelAttempt(True, True, 0.4)
    first = judge_travel(
        miss, target_m=1.0, tolerance_m=0.05, number=1, show_hints=True, answer=ANSWER
    )
    third = judge_travel(
        miss, target_m=1.0, tolerance_m=0.05, number=3, show_hints=True, answer=ANSWER
    )
    off = judge_travel(
        miss, target_m=1.0, tolerance_m=0.05, number=1, show_hints=False, answer=ANSWER
    )
    assert "velocity × travel_time" in first.hint
    assert "travel_time 5.0" in third.hint
    assert off.hint == ""


def test_params_yaml_is_a_ros_params_file(tmp_path: Path) -> None:
    path = write_params_file(tmp_path / "p.yaml", "/n", {"velocity": 0.2, "travel_time": 5.0})
    data = yaml.safe_load(path.read_text())
    assert data == {"/n": {"ros__parameters": {"travel_time": 5.0, "velocity": 0.2}}}
    assert params_yaml("/n", {"b": 1, "a": True}).splitlines()[2:] == ["    a: true", "    b: 1"]
    assert list(tmp_path.iterdir()) == [path], "no temporary file is left behind"


def test_set_command_types_values_as_ros2cli_parses_them() -> None:
    assert set_command("/n", "velocity", 0.2) == "ros2 param set /n velocity 0.2"
    assert set_command("/n", "flag", False) == "ros2 param set /n flag false"
    assert set_command("/n", "count", 3) == "ros2 param set /n count 3"
    assert set_command("/n", "gains", [1.0, 2.0]) == "ros2 param set /n gains '[1.0, 2.0]'"


@pytest.mark.parametrize(
    "value", ["it's here", "a b", "0.2", "", "$HOME `id`", [1.0, 2.5], ["a b", "c'd"], True, -3]
)
def test_a_set_command_pasted_into_a_shell_sets_exactly_the_value(value: object) -> None:
    """The panel's printed line, split as bash splits it, gives ros2 the value itself."""
    argv = shlex.split(set_command("/n", "p", value))
    assert argv[:5] == ["ros2", "param", "set", "/n", "p"] and len(argv) == 6, argv
    assert yaml.safe_load(argv[5]) == value


def test_atomic_write_never_leaves_half_a_file(tmp_path: Path) -> None:
    target = tmp_path / "f.yaml"
    atomic_write(target, "old\n")

    with pytest.raises(TypeError):
        atomic_write(target, 42)  # type: ignore[arg-type]
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["f.yaml"]


def test_numbered_and_diff() -> None:
    assert numbered("a\nb\n", marks={2}) == "  1 | a\n> 2 | b\n"
    assert "+v: 1" in diff_text("v: 0\n", "v: 1\n", "f.yaml")
