"""Lesson 10's launches: start one, show its first lines as a terminal would, stop it."""

from __future__ import annotations

import html
from typing import Any

from ..core.errors import CourseError
from .files import Text

__all__ = ["LaunchRun", "start_launch"]


class LaunchRun:
    """A running `ros2 launch` started by a lesson."""

    def __init__(
        self, handle: Any, command: str, first_lines: list[str], hints: list[str] | None = None
    ) -> None:
        self.handle = handle
        self.command = command
        self.first_lines = first_lines
        self.hints = hints or []

    def __repr__(self) -> str:
        from ..notebook.hints import as_text

        lines = [f"$ {self.command}", *self.first_lines]
        return "".join(f"{line}\n" for line in lines) + as_text(self.hints)

    def _repr_html_(self) -> str | None:
        """Return the lines and the hints set apart, or None (plain text only) without hints."""
        if not self.hints:
            return None
        from ..notebook.hints import as_html

        lines = [f"$ {self.command}", *self.first_lines]
        body = html.escape("".join(f"{line}\n" for line in lines))
        return f'<pre style="margin:0">{body}</pre>{as_html(self.hints)}'

    def stop(self) -> Text:
        """Stop the launch as Ctrl-C does; launch stops its nodes first."""
        code = self.handle.stop()
        return Text(f"ros2 launch stopped (Ctrl-C), exit code {code}.")


def _planned(package: str, file: str | None, *args: str) -> tuple[list[str], list[str]]:
    """Return the executables the launch file starts and the files its nodes get through
    `--params-file` (read, not run)."""
    from pathlib import Path

    from ..launch.command.dry_run import dry_run
    from ..notebook.hints import params_files

    plans = dry_run(package, file, *args).nodes
    files = [f for plan in plans for f in params_files(plan.cmd)]
    return sorted({Path(plan.cmd[0]).name for plan in plans}), list(dict.fromkeys(files))


def _params_file_hints(handle: Any, files: list[str], before: set[str]) -> list[str]:
    """Return the hints for the launch's params files, checked against its running nodes."""
    import os

    from ..notebook import hints
    from ..ros2.api.nodes_and_params import client

    if not files:
        return []
    now = {n.full_name for n in client().node_names()}
    started = hints.started_nodes(handle.output, before, now)
    return hints.params_file_hints(files, started, client, cwd=os.getcwd())


def start_launch(
    lesson: Any, package: str, file: str | None, *args: str, lines: int = 4
) -> LaunchRun:
    """Start `ros2 launch package file args` (or `ros2 launch path args`); wait for its node."""
    from ..lab.takeover import keep_one_driver, remember, take_over
    from ..launch import launch
    from ..ros2.api import nodes_and_params as api

    executables, files = _planned(package, file, *args)
    for executable in executables:
        taken = take_over(executable)
        if taken:
            print(taken)
    before = {n.full_name for n in api.client().node_names()} if files else set()
    handle = launch(package, file, *args, session=lesson.session)
    lesson.state.setdefault("launches", []).append(handle)  # a failed one too: exercises judge it
    command = " ".join(["ros2", "launch", package, *([file] if file else []), *args])
    if handle.wait_for(r"Velocity parameter is", timeout=15.0) is None:
        tail = "\n".join(handle.output[-8:])
        handle.stop()
        raise CourseError(
            f"The launch did not start its node.\n{tail}", hint="read the lines above."
        )
    for executable in executables:
        remember(handle.child, executable)  # stopping the launch stops its node
    api.client().wait_all_seen(timeout=3.0)
    driver = keep_one_driver(handle.child)
    if driver:
        print(driver)
    value = api.param_get("/param_vel_node", "velocity").value
    lesson.state.setdefault("launch_velocities", []).append(value)
    notes = _params_file_hints(handle, files, before)
    return LaunchRun(handle, command, handle.output[:lines], notes)
