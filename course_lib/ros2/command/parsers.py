"""Argument parsing built the way ros2cli 0.32.2 builds it, so usage, help and errors match (pure).

ros2cli adds a command's (and a verb's) arguments only once a first lenient pass over argv
has picked it; the usage lines argparse prints depend on that, so this module does the same.
"""

from __future__ import annotations

import argparse
import contextvars
import sys
import threading
import types
from collections import OrderedDict
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any, NoReturn, cast

from . import table

__all__ = ["COMMANDS", "ParseExit", "Spec", "output_sink", "parse"]


class ParseExit(Exception):
    """argparse wanted to exit (help printed: 0, bad arguments: 2)."""

    def __init__(self, status: int) -> None:
        super().__init__(status)
        self.status = status


@dataclass
class _Sink:
    stdout: list[str] = field(default_factory=list)
    stderr: list[str] = field(default_factory=list)
    width: int = 80


output_sink: contextvars.ContextVar[_Sink] = contextvars.ContextVar("ros2_parse_sink")


class _Formatter(argparse.RawDescriptionHelpFormatter):
    """Help text wrapped to the width of the console the command prints to."""

    def __init__(self, prog: str, **kwargs: Any) -> None:
        # `width` is HelpFormatter's constructor argument in CPython 3.10-3.13;
        # tests/unit/ros2/command/test_ros2_argparse_tripwires.py fails if that changes.
        sink = output_sink.get(None)
        kwargs.setdefault("width", (sink.width if sink else 80) - 2)
        super().__init__(prog, **kwargs)


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser writing into the current sink and raising instead of exiting.

    Only public methods are overridden (print_help, print_usage, exit, error): argparse
    routes all of its output and exits through them.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs["formatter_class"] = _Formatter
        super().__init__(*args, **kwargs)

    @staticmethod
    def _emit(message: str, file: Any) -> None:
        if message:
            sink = output_sink.get()
            to_stderr = file is _Stderr or file is sys.stderr
            (sink.stderr if to_stderr else sink.stdout).append(message)

    def exit(self, status: int = 0, message: str | None = None) -> NoReturn:
        if message:
            self._emit(message, _Stderr)
        raise ParseExit(status)

    def print_help(self, file: Any = None) -> None:
        self._emit(self.format_help(), file)

    def print_usage(self, file: Any = None) -> None:
        self._emit(self.format_usage(), file)

    def error(self, message: str) -> NoReturn:
        self.print_usage(_Stderr)
        self.exit(2, f"{self.prog}: error: {message}\n")


class _StderrMarker:
    """Stands for sys.stderr inside the parser (output is captured, never written)."""


_Stderr = _StderrMarker()


@dataclass(frozen=True)
class Spec:
    """A command or verb: its one-line doc, the builder of its arguments, its sub-verbs."""

    doc: str
    add_arguments: str | None = None  # `module:function` in course_lib.ros2 (see table)
    verbs: dict[str, Spec] | None = None
    leading: str | None = None


def _spec(command: table.Command) -> Spec:
    verbs = None
    if command.verbs is not None:
        verbs = {name: Spec(v.doc, v.arguments) for name, v in command.verbs.items()}
    own = command.own.arguments if command.own is not None else None
    return Spec(command.doc, own, verbs, command.leading)


COMMANDS: dict[str, Spec] = {name: _spec(c) for name, c in table.COMMANDS.items()}


class _MutableString:
    """A description filled in after the lenient pass (as ros2cli's MutableString)."""

    def __init__(self) -> None:
        self.value = ""

    def __getattr__(self, name: str) -> Any:
        return getattr(self.value, name)

    def __iter__(self) -> Iterator[str]:
        return self.value.__iter__()


def _ignore_zero_exit(original: Callable[..., None]) -> Callable[..., None]:
    def exit_(self: object, status: int = 0, message: str | None = None) -> None:
        if status == 0:
            return
        original(status=status, message=message)

    return exit_


def _lenient_parse(
    root: _Parser, parsers: Sequence[_Parser], argv: list[str]
) -> argparse.Namespace:
    saved = {p: (p.print_help, p.exit) for p in parsers}
    for p in parsers:
        p.print_help = lambda *a, **k: None  # type: ignore[method-assign]
        p.exit = types.MethodType(_ignore_zero_exit(p.exit), p)  # type: ignore[method-assign]
    try:
        known, _ = root.parse_known_args(args=argv)
    finally:
        for p, (help_, exit_) in saved.items():
            p.print_help, p.exit = help_, exit_  # type: ignore[method-assign]
    return known


def _add_on_demand(
    parser: _Parser,
    root: _Parser,
    cli_name: str,
    dest: str,
    specs: dict[str, Spec],
    argv: list[str],
) -> None:
    description = _MutableString()
    sub = parser.add_subparsers(
        title="Commands",
        description=cast(str, description),  # argparse reads it as text, filled in by then
        metavar=f"Call `{cli_name} <command> -h` for more detailed usage.",
    )
    sub.dest = " " + dest.lstrip("_")
    sub.required = False
    children = {name: sub.add_parser(name) for name in sorted(specs)}
    known = _lenient_parse(root, [parser, *children.values()], argv)
    chosen = getattr(known, sub.dest)
    if chosen is None:
        width = max(len(name) for name in specs)
        description.value = "".join(
            f"{name.ljust(width)}  {specs[name].doc}\n" for name in sorted(specs)
        )
        for name, child in children.items():
            child.set_defaults(**{dest: name})
        return
    spec, child = specs[chosen], children[chosen]
    root.chosen_parsers.append(child)  # type: ignore[attr-defined]
    child.set_defaults(**{dest: chosen})
    child.description = spec.doc
    for builder in (spec.leading, spec.add_arguments):
        if builder is not None:
            table.resolve(builder)(child)
    if spec.verbs is not None:
        _add_on_demand(child, root, f"{cli_name} {chosen}", "_verb", spec.verbs, argv)


def build_root() -> _Parser:
    """Return the top-level `ros2` parser (before any command is chosen)."""
    root = _Parser(prog="ros2", description="ros2 is an extensible command-line tool for ROS 2.")
    root.add_argument(
        "--use-python-default-buffering",
        action="store_true",
        default=False,
        help=(
            "Do not force line buffering in stdout and instead use the python default buffering, "
            "which might be affected by PYTHONUNBUFFERED/-u and depends on whatever stdout is "
            "interactive or not"
        ),
    )
    return root


_TREES_KEPT = 32  # parser trees kept, by argv (about 50 KiB each)
_trees: OrderedDict[tuple[str, ...], _Parser] = OrderedDict()
_trees_lock = threading.Lock()


def _tree(argv: list[str]) -> _Parser:
    """Return the parser tree ros2cli builds for `argv` (kept: the same argv, the same tree).

    Building one takes about 2 ms (some 35 parsers), ten times the parse itself; a repeated
    command (a learner's `%ros2 param get`, a terminal's up-arrow) reuses its tree. A tree
    whose lenient pass fails is never kept (its errors are printed again next time).
    """
    key = tuple(argv)
    with _trees_lock:
        root = _trees.get(key)
        if root is not None:
            _trees.move_to_end(key)
            return root
    root = build_root()
    root.chosen_parsers = []  # type: ignore[attr-defined]
    _add_on_demand(root, root, "ros2", "_command", COMMANDS, argv)
    with _trees_lock:
        _trees[key] = root
        while len(_trees) > _TREES_KEPT:
            _trees.popitem(last=False)
    return root


def parse(argv: list[str]) -> tuple[argparse.Namespace | None, _Parser]:
    """Parse argv as `ros2` does; raise ParseExit when argparse would exit.

    Returns the namespace (with `_command` and `_verb` names) and the innermost chosen
    parser, whose help ros2cli prints when a command is given without a verb.
    """
    root = _tree(argv)
    args = root.parse_args(args=argv)
    chosen = root.chosen_parsers  # type: ignore[attr-defined]
    return args, chosen[0] if chosen else root
