"""`lesson.run(...)`: start a node like `ros2 run` and show what its terminal would show."""

from __future__ import annotations

import html
import os
import shlex
from typing import Any

__all__ = ["RUN_PREFIX", "LogLines", "run_node"]

RUN_PREFIX = "[ros2run]:"


class LogLines:
    """Log lines of a node, shown as its terminal shows them (then the course's hints)."""

    def __init__(self, lines: list[str], hints: list[str] | None = None) -> None:
        self.lines = lines
        self.hints = hints or []

    def __repr__(self) -> str:
        from ..notebook.hints import as_text

        return "".join(f"{line}\n" for line in self.lines) + as_text(self.hints)

    def _repr_html_(self) -> str | None:
        """Return the lines and the hints set apart, or None (plain text only) without hints."""
        if not self.hints:
            return None
        from ..notebook.hints import as_html

        body = html.escape("".join(f"{line}\n" for line in self.lines))
        return f'<pre style="margin:0">{body}</pre>{as_html(self.hints)}'


def run_node(
    lesson: Any, package: str, executable: str, *args: str, timeout: float = 10.0
) -> LogLines:
    """Start a node like `ros2 run` for `lesson`; return its first log line, or how it failed."""
    from ..lab.takeover import keep_one_driver, remember, take_over
    from ..notebook import hints
    from ..ros2.api.nodes_and_params import client

    command = " ".join(shlex.quote(a) for a in ("ros2", "run", package, executable, *args))
    taken = take_over(executable)
    if taken:
        print(taken)
    files = hints.params_files(args)
    before = {n.full_name for n in client().node_names()} if files else set()
    child = lesson.session.run(package, executable, *args, cwd=os.getcwd())
    lesson.started[executable] = child
    child.wait_for_start(timeout)  # a node failing at start-up: to its last line
    first = None
    if child.alive:
        first = child.wait_for_line(lambda line: line.text.startswith("["), timeout)
    if first is not None and child.alive:
        remember(child, executable)
        client().wait_all_seen(timeout=3.0)
        driver = keep_one_driver(child)
        if driver:
            print(driver)
        notes: list[str] = []
        if files:
            now = {n.full_name for n in client().node_names()}
            started = hints.started_nodes((ln.text for ln in child.lines), before, now)
            notes = hints.params_file_hints(files, started, client, cwd=os.getcwd())
        return LogLines([f"$ {command}", first.text], notes)
    code = child.wait(timeout)
    last = [ln.text for ln in child.lines if ln.text.strip()][-1:]
    hint = hints.crash_hint(last, files, cwd=os.getcwd())
    return LogLines(
        [f"$ {command}", *last, f"{RUN_PREFIX} Process exited with failure {code}"],
        [hint] if hint else [],
    )
