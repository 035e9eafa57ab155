"""Run one `ros2 ...` command line: parse it as ros2cli does, then call the verb (any door)."""

from __future__ import annotations

import argparse
import traceback
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from . import parsers
from .console import CollectingConsole, Console
from .results import CommandOutput

__all__ = ["Context", "execute", "run_collected"]

# Verbs that need no ROS graph (and so no rclpy) at all.
LOCAL_VERBS = {("pkg", "executables"), ("pkg", "prefix")}


@dataclass
class Context:
    """What a verb may use: the console, a ROS client made on first use, the caller's cwd/env."""

    console: Console
    client_factory: Callable[[], Any] | None = None
    cwd: str | None = None
    env: Mapping[str, str] = field(default_factory=dict)
    background_run: Callable[..., Any] | None = None
    _client: Any = None

    @property
    def client(self) -> Any:
        """Return the RosClient (created on first use)."""
        if self._client is None:
            if self.client_factory is None:
                raise RuntimeError("this door has no ROS client")
            self._client = self.client_factory()
        return self._client


def _handler(command: str, verb: str | None) -> Callable[[argparse.Namespace, Context], Any]:
    from . import daemon_verbs, pkg, topics, verbs

    table: dict[tuple[str, str | None], Callable[[argparse.Namespace, Context], Any]] = {
        ("node", "list"): verbs.node_list,
        ("node", "info"): verbs.node_info,
        ("topic", "list"): verbs.topic_list,
        ("topic", "echo"): topics.topic_echo,
        ("topic", "hz"): topics.topic_hz,
        ("param", "list"): verbs.param_list,
        ("param", "get"): verbs.param_get,
        ("param", "set"): verbs.param_set,
        ("param", "describe"): verbs.param_describe,
        ("param", "dump"): verbs.param_dump,
        ("param", "load"): verbs.param_load,
        ("param", "delete"): verbs.param_delete,
        ("pkg", "executables"): pkg.pkg_executables,
        ("pkg", "prefix"): pkg.pkg_prefix,
        ("run", None): pkg.run,
        ("daemon", "start"): daemon_verbs.daemon_start,
        ("daemon", "status"): daemon_verbs.daemon_status,
        ("daemon", "stop"): daemon_verbs.daemon_stop,
    }
    found = table.get((command, verb))
    if found is None:
        return _not_available
    return found


def _not_available(args: argparse.Namespace, ctx: Context) -> str:
    words = " ".join(w for w in (args._command, getattr(args, "_verb", None)) if w)
    return (
        f"`ros2 {words}` is not part of this course's ros2 commands "
        "(it has: daemon, node, topic list|echo|hz, param, pkg executables|prefix, run, launch)."
    )


def _finish(rc: Any, console: Console) -> int:
    """Turn a verb's return value into an exit code, as `sys.exit(rc)` would."""
    if rc is None:
        return 0
    if isinstance(rc, str):
        console.err(rc + "\n")
        return 1
    return int(rc) & 0xFF


def _crash(console: Console, exc: BaseException) -> int:
    """Show an unexpected error the way an uncaught exception ends the real tool."""
    lines = traceback.format_exception_only(type(exc), exc)
    console.err("Traceback (most recent call last):\n" + "".join(lines))
    return 1


def command_of(argv: list[str]) -> str | None:
    """Return the command word of a `ros2` argv (skipping the one top-level option)."""
    for word in argv:
        if word != "--use-python-default-buffering":
            return None if word.startswith("-") else word
    return None


def launch(argv: list[str], console: Console) -> int:
    """Hand `ros2 launch ...` to course_lib.launch (it prints straight to this process)."""
    rest = argv[argv.index("launch") + 1 :]
    try:
        from ..launch import cli as launch_cli
    except ImportError as exc:
        console.err(f"ros2 launch is not available in this course yet ({exc}).\n")
        return 1
    return int(launch_cli.main(rest) or 0)


def execute(argv: list[str], ctx: Context) -> int:
    """Run `ros2 <argv>` writing to ctx.console; return the exit code."""
    if command_of(argv) == "launch":
        return launch(argv, ctx.console)
    sink = parsers._Sink(width=ctx.console.width)
    token = parsers.output_sink.set(sink)
    try:
        args, parser = parsers.parse(list(argv))
        status = None
    except parsers.ParseExit as exc:
        args, parser, status = None, None, exc.status
    finally:
        parsers.output_sink.reset(token)
    for stream, chunks in (("out", sink.stdout), ("err", sink.stderr)):
        if chunks:
            getattr(ctx.console, stream)("".join(chunks))
    if status is not None:
        return status
    assert args is not None and parser is not None
    command = getattr(args, "_command", None)
    spec = parsers.COMMANDS.get(command) if command else None
    verb = getattr(args, "_verb", None)
    if command is None or (spec is not None and spec.verbs is not None and verb is None):
        help_token = parsers.output_sink.set(sink)
        try:
            ctx.console.out(parser.format_help())
        finally:
            parsers.output_sink.reset(help_token)
        return 0
    try:
        return _finish(_handler(command, verb)(args, ctx), ctx.console)
    except KeyboardInterrupt:
        return 2  # ros2cli returns signal.SIGINT
    except Exception as exc:
        message = getattr(exc, "cli_message", None)
        if message:
            return _finish(message, ctx.console)
        return _crash(ctx.console, exc)


def run_collected(
    argv: list[str],
    *,
    client_factory: Callable[[], Any] | None = None,
    cwd: str | None = None,
    width: int = 80,
) -> CommandOutput:
    """Run `ros2 <argv>` and return everything it printed with its exit code."""
    console = CollectingConsole(width=width)
    code = execute(argv, Context(console, client_factory, cwd))
    return console.result(code)
