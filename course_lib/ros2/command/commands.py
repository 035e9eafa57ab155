"""Run one `ros2 ...` command line: parse it as ros2cli does, then call the verb (any door)."""

from __future__ import annotations

import argparse
import difflib
import traceback
from collections.abc import Callable
from typing import Any

from ..results import CommandOutput
from ..verbkit.console import CollectingConsole, Console
from ..verbkit.context import Context
from . import parsers, table

__all__ = ["Context", "execute", "not_in_course", "run_collected"]


def _handler(command: str, verb: str | None) -> Callable[[argparse.Namespace, Context], Any]:
    entry = table.COMMANDS[command]
    chosen = entry.own if entry.verbs is None else entry.verbs[verb or ""]
    assert chosen is not None
    return table.resolve(chosen.handler)


def _has() -> str:
    return f"This course's ros2 has: {', '.join(table.available())} (see `ros2 --help`).\n"


def not_in_course(argv: list[str]) -> tuple[str, int] | None:
    """Return (message, exit code) for a command or verb the course lacks, else None."""
    command, verb = table.verb_of(argv)
    if command is None:
        return None
    if command not in table.COMMANDS:
        hint = table.absent_hint(command)
        if hint is not None:
            return f"`ros2 {command}` is not part of this course's ros2. {hint}\n" + _has(), 1
        real = [*table.COMMANDS, *(w for w in table.ELSEWHERE if " " not in w)]
        close = difflib.get_close_matches(command, real, n=1)
        guess = f" Did you mean `ros2 {close[0]}`?" if close else ""
        return f"ros2: unknown command '{command}'.{guess}\n" + _has(), 2
    hint = table.absent_hint(f"{command} {verb}") if verb else None
    if hint is not None:
        return f"`ros2 {command} {verb}` is not part of this course's ros2. {hint}\n" + _has(), 1
    return None


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


def execute(argv: list[str], ctx: Context) -> int:
    """Run `ros2 <argv>` writing to ctx.console; return the exit code."""
    command = command_of(argv)
    raw = table.COMMANDS[command].raw if command in table.COMMANDS else None
    if command is not None and raw is not None:
        return int(table.resolve(raw)(argv[argv.index(command) + 1 :], ctx) or 0)
    refused = not_in_course(argv)
    if refused is not None:
        ctx.console.err(refused[0])
        return refused[1]
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
    except RuntimeError as exc:  # ros2cli prints a verb's RuntimeError and exits 1
        return _finish(getattr(exc, "cli_message", None) or str(exc), ctx.console)
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
