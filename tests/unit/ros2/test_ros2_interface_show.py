"""`ros2 interface show|proto|list|package(s)` against the golden transcripts, without ROS."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from course_lib.ros2.command.commands import run_collected
from course_lib.ros2.interface_text import show_lines
from course_lib.tools.testing import with_course_interfaces, with_course_services

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


def _installed_lines() -> list[tuple[str, str]]:
    share = Path(sys.prefix) / "share"
    files = sorted(share.glob("*/msg/*.msg")) + sorted(share.glob("*/srv/*.srv"))
    return [
        (f.parts[-3], line.rstrip())
        for f in files
        for line in f.read_text().splitlines()
        if line.rstrip() != "---"
    ]


def test_line_rules_agree_with_rosidl_adapter() -> None:
    """Every line of every installed .msg/.srv is judged as rosidl_adapter's parser does."""
    parser = pytest.importorskip("rosidl_adapter.parser")
    from course_lib.ros2 import interface_text

    lines = _installed_lines()
    assert len(lines) > 1000
    for package, line in lines:
        spec = parser.parse_message_string(package, "X", line)
        element = (spec.fields or spec.constants or [None])[0]
        trailing = element.annotations.get("comment") if element is not None else None
        nested = None
        if spec.fields and "/" in str(spec.fields[0].type):
            nested = str(spec.fields[0].type).split("[")[0].replace("/", "/msg/")
        assert interface_text._is_comment(line) == bool(spec.annotations["comment"]), line
        assert interface_text._trailing(line) == (trailing[0] if trailing else None), line
        assert interface_text._nested(line, package) == nested, line


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
