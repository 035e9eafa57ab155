"""`%ros2` and `%%ros2` in notebooks: the command after a prompt, output as a terminal shows it.

The plain-text form of each result is exactly what the real `ros2` prints (stdout then
stderr), so nbval can compare it; the HTML form adds the prompt, red stderr and the exit code.
"""

from __future__ import annotations

import html
import shlex
from typing import Any

from ..core.param_journal import acting_door
from ..ros2.results import CommandOutput

__all__ = ["CommandResult", "load_ipython_extension", "run_line"]

_STYLE = "font-family:monospace;white-space:pre-wrap;margin:0"


class CommandResult:
    """One command and its output, displayed like a terminal (plain text: the output only)."""

    def __init__(self, command: str, output: CommandOutput) -> None:
        self.command = command
        self.output = output

    def __repr__(self) -> str:
        return self.output.text

    def _repr_html_(self) -> str:
        parts = [
            f'<div style="{_STYLE}"><span style="color:#2e7d32">$ </span>'
            f"<b>{html.escape(self.command)}</b>"
        ]
        if self.output.stdout:
            parts.append(f'<pre style="{_STYLE}">{html.escape(self.output.stdout)}</pre>')
        if self.output.stderr:
            parts.append(
                f'<pre style="{_STYLE};color:#c62828">{html.escape(self.output.stderr)}</pre>'
            )
        if self.output.exit_code:
            parts.append(f'<span style="color:#c62828">[exit code {self.output.exit_code}]</span>')
        return "".join(parts) + "</div>"


RUN_SEEN_WAIT_S = 3.0  # at most, after the node's first line, until this kernel has seen it


def _background_run(cmd: list[str], name: str, ctx: Any) -> int:
    """Start `ros2 run`'s executable as a session child and show its first lines.

    A node of the same executable that a lesson left running is stopped first, and so is any
    other lessons' node that drives the robot when this one does (a line says so, printed
    apart from the command's own output).
    """
    from ..lab.takeover import keep_one_driver, remember, take_over
    from ..session.session import get_session

    taken = take_over(name)
    if taken:
        print(taken)
    child = get_session().spawn(cmd, name=name, cwd=ctx.cwd)
    child.wait_for_line(lambda _line: True, timeout=3.0)
    remember(child, name)
    if child.alive:  # the next command (`%ros2 node list`) sees the new node, even under load
        from ..ros2.api.nodes_and_params import client

        client().wait_all_seen(timeout=RUN_SEEN_WAIT_S)
        driver = keep_one_driver(child)
        if driver:
            print(driver)
    for line in child.lines[:5]:
        (ctx.console.err if line.stream == "stderr" else ctx.console.out)(line.text + "\n")
    return 0 if child.alive else int(child.returncode or 0)


def run_line(line: str) -> CommandResult:
    """Run one `ros2 ...` line (the leading `ros2` is optional) in this kernel's session."""
    from ..ros2.api.nodes_and_params import client
    from ..ros2.command.commands import Context, execute
    from ..ros2.verbs.console import CollectingConsole

    argv = shlex.split(line)
    if argv and argv[0] == "ros2":
        argv = argv[1:]
    command = "ros2 " + " ".join(shlex.quote(a) for a in argv)
    console = CollectingConsole(width=80)
    ctx = Context(console, client, background_run=_background_run)
    with acting_door("%ros2"):
        return CommandResult(command, console.result(execute(argv, ctx)))


def _ros2_magic(line: str, cell: str | None = None) -> Any:
    from IPython.display import display

    lines = [line] if cell is None else [ln for ln in cell.splitlines() if ln.strip()]
    for text in lines:
        if text.strip().startswith("#"):
            continue
        result = run_line(text)
        # raw: IPython's plain-text formatter would drop the final newline the CLI prints
        display({"text/plain": result.output.text, "text/html": result._repr_html_()}, raw=True)


def load_ipython_extension(ipython: Any) -> None:
    """Register `%ros2` and `%%ros2` (run `%load_ext course_lib.notebook.magics`)."""
    ipython.register_magic_function(
        lambda line: _ros2_magic(line), magic_kind="line", magic_name="ros2"
    )
    ipython.register_magic_function(
        lambda line, cell: _ros2_magic(line, cell), magic_kind="cell", magic_name="ros2"
    )
