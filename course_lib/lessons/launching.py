"""Lesson 10's launches: start one, show its first lines as a terminal would, stop it."""

from __future__ import annotations

from typing import Any

from ..core.errors import CourseError
from .files import Text

__all__ = ["LaunchRun", "start_launch"]


class LaunchRun:
    """A running `ros2 launch` started by a lesson."""

    def __init__(self, handle: Any, command: str, first_lines: list[str]) -> None:
        self.handle = handle
        self.command = command
        self.first_lines = first_lines

    def __repr__(self) -> str:
        return "".join(f"{line}\n" for line in [f"$ {self.command}", *self.first_lines])

    def stop(self) -> Text:
        """Stop the launch as Ctrl-C does; launch stops its nodes first."""
        code = self.handle.stop()
        return Text(f"ros2 launch stopped (Ctrl-C), exit code {code}.")


def _executables(package: str, file: str | None, *args: str) -> list[str]:
    """Return the names of the executables the launch file starts (read, not run)."""
    from pathlib import Path

    from ..launch.command.dry_run import dry_run

    return sorted({Path(plan.cmd[0]).name for plan in dry_run(package, file, *args).nodes})


def start_launch(
    lesson: Any, package: str, file: str | None, *args: str, lines: int = 4
) -> LaunchRun:
    """Start `ros2 launch package file args` (or `ros2 launch path args`); wait for its node."""
    from ..lab.takeover import keep_one_driver, remember, take_over
    from ..launch import launch
    from ..ros2.api import nodes_and_params as api

    executables = _executables(package, file, *args)
    for executable in executables:
        taken = take_over(executable)
        if taken:
            print(taken)
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
    return LaunchRun(handle, command, handle.output[:lines])
