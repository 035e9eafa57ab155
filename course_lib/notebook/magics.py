"""`%ros2` and `%%ros2` in notebooks: the command after a prompt, output as a terminal shows it.

The plain-text form of each result is exactly what the real `ros2` prints (stdout then
stderr), so nbval can compare it; the HTML form adds the prompt, the exit code, and colours
stderr's lines as ROS's colourised log does: a log line by its severity (`[INFO]` in the text's
own colour, `[WARN]` amber), any other line (a failure, a traceback) red.
After a mistake, a course hint (`hints.py`) follows on its own line: `Hint: ...` in plain text,
a blue line apart in HTML; Jazzy's text above it is unchanged.
"""

from __future__ import annotations

import functools
import html
import os
import re
import shlex
import time
from collections.abc import Sequence
from typing import Any

from ..core.param_journal import acting_door
from ..ros2.results import CommandOutput
from . import hints as course_hints

__all__ = ["ERROR_COLOUR", "CommandResult", "load_ipython_extension", "run_line", "stderr_html"]

_STYLE = "font-family:monospace;white-space:pre-wrap;margin:0"
ERROR_COLOUR = "#c62828"  # 5.6:1 on white, as every colour here (WCAG AA: 4.5:1)
# a log line's severity, after a launched process's `[name-N] ` prefix if any; none: red
_SEVERITY = re.compile(r"^(?:\[[\w.-]+-\d+\] )?\[(DEBUG|INFO|WARN|ERROR|FATAL)\]")
_COLOURS = {"DEBUG": "", "INFO": "", "WARN": "#8a4b00", "ERROR": ERROR_COLOUR}


def stderr_html(text: str) -> str:
    """Return stderr as one `<pre>`, runs of lines of one colour in a span each (the text is
    unchanged: only its presentation differs from stdout's)."""
    runs: list[tuple[str, str]] = []
    for line in text.splitlines(keepends=True):
        found = _SEVERITY.match(line)
        colour = _COLOURS.get(found[1], ERROR_COLOUR) if found else ERROR_COLOUR
        if runs and runs[-1][0] == colour:
            runs[-1] = (colour, runs[-1][1] + line)
        else:
            runs.append((colour, line))
    body = "".join(
        f'<span style="color:{colour}">{html.escape(run)}</span>' if colour else html.escape(run)
        for colour, run in runs
    )
    return f'<pre class="stderr" style="{_STYLE}">{body}</pre>'


class CommandResult:
    """One command and its output, displayed like a terminal (plain text: the output, then
    the course's hints, if any)."""

    def __init__(self, command: str, output: CommandOutput, hints: Sequence[str] = ()) -> None:
        self.command = command
        self.output = output
        self.hints = list(hints)

    @property
    def text(self) -> str:
        """Return Jazzy's text (stdout then stderr), then one `Hint: ...` line per hint."""
        return self.output.text + course_hints.as_text(self.hints)

    def __repr__(self) -> str:
        return self.text

    def _repr_html_(self) -> str:
        parts = [
            f'<div style="{_STYLE}"><span style="color:#2e7d32">$ </span>'
            f"<b>{html.escape(self.command)}</b>"
        ]
        if self.output.stdout:
            parts.append(f'<pre style="{_STYLE}">{html.escape(self.output.stdout)}</pre>')
        if self.output.stderr:
            parts.append(stderr_html(self.output.stderr))
        if self.output.exit_code:
            code = self.output.exit_code
            parts.append(f'<span style="color:{ERROR_COLOUR}">[exit code {code}]</span>')
        return "".join(parts) + course_hints.as_html(self.hints) + "</div>"


RUN_SEEN_WAIT_S = 3.0  # at most, after the node's first line, until this kernel has seen it
FILE_RUN_WAIT_S = 10.0  # at most, with `--params-file`, for the first line or the crash
RUN_FIRST_WAIT_S = 3.0  # for the first line of a node that starts at its usual speed
SLOW_START_WAIT_S = 15.0  # in all, for a node still starting (silent, not yet in the graph)
FIRST_WORDS_GRACE_S = 2.0  # after a silent node appears in the graph, for its first line


def _started(child: Any, before: set[str]) -> list[str]:
    """Return the nodes `child` started (see `hints.started_nodes`)."""
    from ..ros2.api.nodes_and_params import client

    now = {n.full_name for n in client().node_names()}
    return course_hints.started_nodes((ln.text for ln in child.lines), before, now)


def _wait_for_a_slow_start(child: Any) -> None:
    """Wait on for the first line of a node still starting (a busy host can take more than
    RUN_FIRST_WAIT_S to start Python, rclpy and the node), since a line that comes after the
    magic returns is shown nowhere. A node that is silent by design stops the wait once the
    graph shows a node of `child`'s process (its /rosout publisher, made first), then
    FIRST_WORDS_GRACE_S more for a first line; the wait ends at SLOW_START_WAIT_S after the
    start in any case."""
    from ..lab.drivers import publishers
    from ..ros2.api.nodes_and_params import client

    deadline = time.monotonic() + SLOW_START_WAIT_S - RUN_FIRST_WAIT_S
    while child.alive and time.monotonic() < deadline:
        if child.wait_for_start(0.25, crash_wait=FILE_RUN_WAIT_S) is not None:
            return
        if any(p.runs_in(child.pid) for p in publishers(client(), "/rosout")):
            child.wait_for_start(FIRST_WORDS_GRACE_S, crash_wait=FILE_RUN_WAIT_S)
            return


def _background_run(cmd: list[str], name: str, ctx: Any, *, notes: list[str]) -> int:
    """Start `ros2 run`'s executable as a session child and show its first lines.

    A node of the same executable that a lesson left running is stopped first, and so is any
    other lessons' node that drives the robot when this one does (a line says so, printed
    apart from the command's own output). A `--params-file` that sets nothing on the nodes it
    started, or whose value of the wrong type stopped the node, adds a hint to `notes`.
    """
    from ..lab.takeover import keep_one_driver, remember, take_over
    from ..ros2.api.nodes_and_params import client
    from ..session.session import get_session

    taken = take_over(name)
    if taken:
        print(taken)
    files = course_hints.params_files(cmd)
    before = {n.full_name for n in client().node_names()} if files else set()
    child = get_session().spawn(cmd, name=name, cwd=ctx.cwd)
    # a params file's hint needs the node's first line (or its traceback): wait longer for it;
    # a node failing at start-up is waited for to its end (its last line says why)
    first = child.wait_for_start(
        FILE_RUN_WAIT_S if files else RUN_FIRST_WAIT_S, crash_wait=FILE_RUN_WAIT_S
    )
    if first is None:
        _wait_for_a_slow_start(child)
    remember(child, name)
    if child.alive:  # the next command (`%ros2 node list`) sees the new node, even under load
        client().wait_all_seen(timeout=RUN_SEEN_WAIT_S)
        driver = keep_one_driver(child)
        if driver:
            print(driver)
        if files:
            notes += course_hints.params_file_hints(
                files, _started(child, before), client, cwd=ctx.cwd
            )
    elif files:
        hint = course_hints.crash_hint(
            (ln.text for ln in child.lines), files, cwd=ctx.cwd or os.getcwd()
        )
        notes += [hint] if hint else []
    # a running node: its first lines; one that ended: all it said, as a terminal shows it
    for line in child.lines[:5] if child.alive else child.lines:
        (ctx.console.err if line.stream == "stderr" else ctx.console.out)(line.text + "\n")
    return 0 if child.alive else int(child.returncode or 0)


def run_line(line: str) -> CommandResult:
    """Run one `ros2 ...` line (the leading `ros2` is optional) in this kernel's session."""
    from ..ros2.api.nodes_and_params import client
    from ..ros2.command.commands import Context, execute
    from ..ros2.verbkit.console import CollectingConsole
    from ..session.session import get_session

    argv = shlex.split(line)
    if argv and argv[0] == "ros2":
        argv = argv[1:]
    command = "ros2 " + " ".join(shlex.quote(a) for a in argv)
    console = CollectingConsole(width=80)
    notes: list[str] = []
    ctx = Context(
        console,
        client,
        env=get_session().env,  # this kernel's session: its domain, whatever os.environ says
        background_run=functools.partial(_background_run, notes=notes),
    )
    with acting_door("%ros2"):
        output = console.result(execute(argv, ctx))
    hint = course_hints.command_hint(argv, output.stdout, output.stderr, client)
    return CommandResult(command, output, [*notes, *([hint] if hint else [])])


def _ros2_magic(line: str, cell: str | None = None) -> Any:
    from IPython.display import display

    lines = [line] if cell is None else [ln for ln in cell.splitlines() if ln.strip()]
    for text in lines:
        if text.strip().startswith("#"):
            continue
        result = run_line(text)
        # raw: IPython's plain-text formatter would drop the final newline the CLI prints
        display({"text/plain": result.text, "text/html": result._repr_html_()}, raw=True)


def load_ipython_extension(ipython: Any) -> None:
    """Register `%ros2` and `%%ros2` (run `%load_ext course_lib.notebook.magics`)."""
    ipython.register_magic_function(
        lambda line: _ros2_magic(line), magic_kind="line", magic_name="ros2"
    )
    ipython.register_magic_function(
        lambda line, cell: _ros2_magic(line, cell), magic_kind="cell", magic_name="ros2"
    )
