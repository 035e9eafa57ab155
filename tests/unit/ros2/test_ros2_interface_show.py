"""`ros2 interface show|proto|list|package(s)` against the golden transcripts, without ROS."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
from course_goldens import with_course_interfaces, with_course_services

from course_lib.ros2.command.commands import run_collected
from course_lib.ros2.interface_text import show_lines

GOLDEN = Path(__file__).resolve().parents[2] / "golden" / "ros2" / "cases_part2.json"
CASES = {c["case"]: c for c in json.loads(GOLDEN.read_text())}
INTERFACE = sorted(n for n, c in CASES.items() if c["command"].startswith("ros2 interface "))


def _run(command: str) -> tuple[str, str, int]:
    argv = command.split()[1:]
    out = run_collected(argv)
    return out.stdout, out.stderr.replace(sys.prefix, "<venv>"), out.exit_code


@pytest.mark.parametrize("name", INTERFACE)
def test_interface_case_matches(name: str) -> None:
    case = CASES[name]
    stdout, stderr, code = _run(case["command"])
    if " package " in case["command"]:  # ros2interface prints a set: its order is random
        stdout, expected = sorted(stdout.splitlines()), sorted(case["stdout"].splitlines())
    elif case["command"] == "ros2 interface packages":
        expected = with_course_interfaces(case["stdout"])
    elif case["command"] == "ros2 interface list -s":
        expected = with_course_services(case["stdout"])
    else:
        expected = case["stdout"]
    assert (stdout, stderr, code) == (expected, case["stderr"], case["exit"])


FILES = {
    "p/msg/A": "# top comment\n#\nint32 x 3 # the x [m]\nB[<=1] b\n\n# [m]\n#   \n  # indented\n",
    "p/msg/B": "#\n# inner\nstring s\nuint8 K=1 # a constant\n",
}


def test_no_comments_keeps_bare_hashes_and_nested_tabs() -> None:
    # A trailing comment is cut one character before its text, as ros2interface does
    # (`int32 x 3 #`); a line is judged after its trailing blanks are stripped.
    lines = list(show_lines("p/msg/A", FILES.__getitem__, comments=False))
    assert lines == [
        "#",
        "int32 x 3 #",
        "B[<=1] b",
        "\t#",
        "\tstring s",
        "\tuint8 K=1 #",
        "# [m]",
        "#",
        "  # indented",
    ]


def test_lines_are_judged_by_rosidl_adapter_as_ros2_does() -> None:
    """The rules ros2interface gets from rosidl_adapter's parser, on the lines that test them."""
    from course_lib.ros2.interface_text import _judge, _Line

    assert _judge("# a comment", "p") == _Line(is_comment=True)
    for not_a_comment in ("#", "####", "# [m]", "  # indented", "---", ""):
        assert _judge(not_a_comment, "p") == _Line(), not_a_comment
    assert _judge("int32 x 3 # the x [m]", "p") == _Line(trailing="the x")
    assert _judge("uint8 K=1 # a constant", "p") == _Line(trailing="a constant")
    assert _judge("B[<=1] b", "p") == _Line(nested="p/msg/B")
    assert _judge("geometry_msgs/Vector3 v  # m/s", "p") == _Line(
        trailing="m/s", nested="geometry_msgs/msg/Vector3"
    )
    assert _judge("string<=5 s", "p") == _judge("float64[] xs #", "p") == _Line()


def test_all_comments_reach_nested_definitions() -> None:
    lines = list(show_lines("p/msg/A", FILES.__getitem__, nested_comments=True))
    assert lines[4:8] == ["\t#", "\t# inner", "\tstring s", "\tuint8 K=1 # a constant"]
    plain = list(show_lines("p/msg/A", FILES.__getitem__))
    assert plain[:5] == ["# top comment", "#", "int32 x 3 # the x [m]", "B[<=1] b", "\t#"]
    assert "\t# inner" not in plain


def test_bad_names_fail_like_ros2() -> None:
    assert _run("ros2 interface show nope") == (
        "",
        "Invalid name 'nope'. Expected three parts separated by '/'\n",
        1,
    )
    assert _run("ros2 interface show no_pkg/msg/X")[1:] == ("Unknown package 'no_pkg'\n", 1)
    assert _run("ros2 interface package no_pkg")[1:] == ("Unknown package 'no_pkg'\n", 1)
