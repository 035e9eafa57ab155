"""Argument parsing built the way ros2cli 0.32.2 builds it, so usage, help and errors match (pure).

ros2cli adds a command's (and a verb's) arguments only once a first lenient pass over argv
has picked it; the usage lines argparse prints depend on that, so this module does the same.
"""

from __future__ import annotations

import argparse
import contextvars
import sys
import types
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from . import verb_args

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


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser writing into the current sink and raising instead of exiting."""

    def _print_message(self, message: str, file=None) -> None:  # type: ignore[no-untyped-def]
        if message:
            sink = output_sink.get()
            to_stderr = file is _Stderr or file is sys.stderr
            (sink.stderr if to_stderr else sink.stdout).append(message)

    def exit(self, status: int = 0, message: str | None = None):  # type: ignore[no-untyped-def]
        if message:
            self._print_message(message, _Stderr)
        raise ParseExit(status)

    def print_help(self, file=None) -> None:  # type: ignore[no-untyped-def]
        self._print_message(self.format_help(), file)

    def print_usage(self, file=None) -> None:  # type: ignore[no-untyped-def]
        self._print_message(self.format_usage(), file)

    def error(self, message: str):  # type: ignore[no-untyped-def]
        self.print_usage(_Stderr)
        self.exit(2, f"{self.prog}: error: {message}\n")

    def _get_formatter(self) -> argparse.HelpFormatter:
        return self.formatter_class(prog=self.prog, width=output_sink.get().width - 2)


class _StderrMarker:
    """Stands for sys.stderr inside the parser (output is captured, never written)."""


_Stderr = _StderrMarker()


@dataclass(frozen=True)
class Spec:
    """A command or verb: its one-line doc, how to add its arguments, its sub-verbs."""

    doc: str
    add_arguments: Callable[[argparse.ArgumentParser], None] | None = None
    verbs: dict[str, Spec] | None = None
    leading: Callable[[argparse.ArgumentParser], None] | None = None


_DAEMON = {
    "start": "Start the daemon if it isn't running",
    "status": "Output the status of the daemon",
    "stop": "Stop the daemon if it is running",
}
_NODE = {"info": "Output information about a node", "list": "Output a list of available nodes"}
_PARAM = {
    "delete": "Delete parameter",
    "describe": "Show descriptive information about declared parameters",
    "dump": "Show all of the parameters of a node in a YAML file format",
    "get": "Get parameter",
    "list": "Output a list of available parameters",
    "load": "Load parameter file for a node",
    "set": "Set parameter",
}
_PKG = {
    "create": "Create a new ROS 2 package",
    "executables": "Output a list of package specific executables",
    "list": "Output a list of available packages",
    "prefix": "Output the prefix path of a package",
    "xml": "Output the XML of the package manifest or a specific tag",
}
_TOPIC = {
    "bw": "Display bandwidth used by topic",
    "delay": "Display delay of topic from timestamp in header",
    "echo": "Output messages from a topic",
    "find": "Output a list of available topics of a given type",
    "hz": "Print the average publishing rate to screen",
    "info": "Print information about a topic",
    "list": "Output a list of available topics",
    "pub": "Publish a message to a topic",
    "type": "Print a topic's type",
}


def _prefixed(prefix: str, verbs: dict[str, str]) -> dict[str, Spec]:
    return {
        name: Spec(doc, getattr(verb_args, f"{prefix}_{name}", None))
        for name, doc in verbs.items()
    }


COMMANDS: dict[str, Spec] = {
    "action": Spec("Various action related sub-commands"),
    "component": Spec("Various component related sub-commands"),
    "daemon": Spec("Various daemon related sub-commands", verbs=_prefixed("daemon", _DAEMON)),
    "doctor": Spec("Check ROS setup and other potential issues"),
    "extension_points": Spec("List extension points"),
    "extensions": Spec("List extensions"),
    "interface": Spec("Show information about ROS interfaces"),
    "launch": Spec("Run a launch file"),
    "lifecycle": Spec("Various lifecycle related sub-commands"),
    "multicast": Spec("Various multicast related sub-commands"),
    "node": Spec("Various node related sub-commands", verbs=_prefixed("node", _NODE)),
    "param": Spec("Various param related sub-commands", verbs=_prefixed("param", _PARAM)),
    "pkg": Spec("Various package related sub-commands", verbs=_prefixed("pkg", _PKG)),
    "run": Spec("Run a package specific executable", verb_args.run),
    "service": Spec("Various service related sub-commands"),
    "topic": Spec(
        "Various topic related sub-commands",
        verbs=_prefixed("topic", _TOPIC),
        leading=verb_args.topic_command,
    ),
    "wtf": Spec("Use `wtf` as alias to `doctor`"),
}
_HIDDEN = frozenset({"extension_points", "extensions"})


class _MutableString:
    """A description filled in after the lenient pass (as ros2cli's MutableString)."""

    def __init__(self) -> None:
        self.value = ""

    def __getattr__(self, name: str):  # type: ignore[no-untyped-def]
        return getattr(self.value, name)

    def __iter__(self):  # type: ignore[no-untyped-def]
        return self.value.__iter__()


def _ignore_zero_exit(original: Callable[..., None]) -> Callable[..., None]:
    def exit_(self, status: int = 0, message: str | None = None) -> None:  # type: ignore[no-untyped-def]
        if status == 0:
            return
        original(status=status, message=message)

    return exit_


def _lenient_parse(root: _Parser, parsers: Sequence[_Parser], argv: list[str]):  # type: ignore[no-untyped-def]
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
    hidden: frozenset[str] = frozenset(),
) -> None:
    description = _MutableString()
    sub = parser.add_subparsers(
        title="Commands",
        description=description,  # type: ignore[arg-type]
        metavar=f"Call `{cli_name} <command> -h` for more detailed usage.",
    )
    sub.dest = " " + dest.lstrip("_")
    sub.required = False
    children = {
        name: sub.add_parser(name, formatter_class=argparse.RawDescriptionHelpFormatter)
        for name in sorted(specs)
    }
    known = _lenient_parse(root, [parser, *children.values()], argv)
    chosen = getattr(known, sub.dest)
    if chosen is None:
        width = max(len(name) for name in specs if name not in hidden)
        description.value = "".join(
            f"{name.ljust(width)}  {specs[name].doc}\n"
            for name in sorted(specs)
            if name not in hidden
        )
        for name, child in children.items():
            if name not in hidden:
                child.set_defaults(**{dest: name})
        return
    spec, child = specs[chosen], children[chosen]
    root.chosen_parsers.append(child)  # type: ignore[attr-defined]
    child.set_defaults(**{dest: chosen})
    child.description = spec.doc
    if spec.leading is not None:
        spec.leading(child)
    if spec.add_arguments is not None:
        spec.add_arguments(child)
    if spec.verbs is not None:
        _add_on_demand(child, root, f"{cli_name} {chosen}", "_verb", spec.verbs, argv)


def build_root() -> _Parser:
    """Return the top-level `ros2` parser (before any command is chosen)."""
    root = _Parser(
        prog="ros2",
        description="ros2 is an extensible command-line tool for ROS 2.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
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


def parse(argv: list[str]) -> tuple[argparse.Namespace | None, _Parser]:
    """Parse argv as `ros2` does; raise ParseExit when argparse would exit.

    Returns the namespace (with `_command` and `_verb` names) and the innermost chosen
    parser, whose help ros2cli prints when a command is given without a verb.
    """
    root = build_root()
    root.chosen_parsers = []  # type: ignore[attr-defined]
    _add_on_demand(root, root, "ros2", "_command", COMMANDS, argv, _HIDDEN)
    args = root.parse_args(args=argv)
    chosen = root.chosen_parsers  # type: ignore[attr-defined]
    return args, chosen[0] if chosen else root
