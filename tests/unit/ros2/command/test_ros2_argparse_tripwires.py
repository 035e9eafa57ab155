"""Tripwires for the argparse behaviour ros2.command.parsers relies on (issue 14, item 7).

parsers.py overrides only public ArgumentParser methods, but it relies on argparse calling
them for all of its output and exits, and on HelpFormatter's `width` argument. If a Python
release changes that, these tests fail loudly instead of the usage text silently changing.
"""

from __future__ import annotations

import argparse

import pytest

from course_lib.ros2.command import parsers
from course_lib.ros2.command.commands import run_collected


def _capture(width: int = 80) -> tuple[parsers._Sink, object]:
    sink = parsers._Sink(width=width)
    return sink, parsers.output_sink.set(sink)


def test_help_action_goes_through_print_help_then_exit() -> None:
    sink, token = _capture()
    try:
        parser = parsers._Parser(prog="demo")
        with pytest.raises(parsers.ParseExit) as info:
            parser.parse_args(["-h"])
        assert sink.stdout == [parser.format_help()] and not sink.stderr
    finally:
        parsers.output_sink.reset(token)
    assert info.value.status == 0


def test_errors_go_through_error_usage_and_exit_2() -> None:
    sink, token = _capture()
    try:
        parser = parsers._Parser(prog="demo")
        parser.add_argument("x")
        with pytest.raises(parsers.ParseExit) as info:
            parser.parse_args([])
    finally:
        parsers.output_sink.reset(token)
    assert info.value.status == 2
    assert "".join(sink.stderr) == (
        "usage: demo [-h] x\ndemo: error: the following arguments are required: x\n"
    )


def test_help_formatter_takes_the_width() -> None:
    formatter = argparse.HelpFormatter("demo", width=30)
    formatter.add_text("word " * 20)
    assert max(len(line) for line in formatter.format_help().splitlines()) <= 30
    _sink, token = _capture(width=42)
    try:
        text = parsers._Parser(prog="demo", description="x").format_help()
        parser = parsers._Parser(prog="demo")
        parser.add_argument("--flag", action="store_true", help="word " * 30)
        assert max(len(line) for line in parser.format_help().splitlines()) <= 40
    finally:
        parsers.output_sink.reset(token)
    assert text.startswith("usage: demo [-h]")


def test_subparser_invalid_choice_text() -> None:
    """The real tool's text for a mistyped verb (argparse words it; 3.12.8+ drops quotes)."""
    out = run_collected(["param", "bogus"])
    assert out.exit_code == 2
    assert out.stderr.endswith(
        "for more detailed usage.: invalid choice: 'bogus' (choose from 'delete', 'describe', "
        "'dump', 'get', 'list', 'load', 'set')\n"
    )
