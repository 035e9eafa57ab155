"""Launch from a notebook: `launch(...)` runs `ros2 launch` in the background of the session.

Lesson 10 introduces it. The cell returns at once; the handle shows the output and stops the
launch the way Ctrl-C does (launch's own shutdown messages, then every node stops).
"""

from __future__ import annotations

import contextlib
import signal
import sys
from collections.abc import Callable
from typing import Any

from ...core.host.signalling import send
from ...processes.children import ChildProcess, OutputLine

__all__ = ["LaunchHandle", "launch"]


class LaunchHandle:
    """A running `ros2 launch`: its output, its state, and how to stop it."""

    def __init__(self, child: ChildProcess, argv: list[str]) -> None:
        self.child = child
        self.argv = argv

    def __repr__(self) -> str:
        state = "running" if self.alive else f"exited {self.returncode}"
        return f"<LaunchHandle ros2 launch {' '.join(self.argv)} ({state})>"

    @property
    def pid(self) -> int:
        return self.child.pid

    @property
    def alive(self) -> bool:
        return self.child.alive

    @property
    def returncode(self) -> int | None:
        return self.child.returncode

    @property
    def output(self) -> list[str]:
        """Return the lines printed so far (stdout and stderr, without line endings)."""
        return [line.text for line in self.child.lines]

    @property
    def text(self) -> str:
        """Return the output so far as one string."""
        return self.child.text()

    def wait_for(self, pattern: str, timeout: float = 10.0) -> str | None:
        """Wait until an output line matches the regex `pattern`; return it, or None."""
        line = self.child.wait_for_line(pattern, timeout)
        return None if line is None else line.text

    def wait(self, timeout: float | None = None) -> int | None:
        """Wait for the launch to end; return its exit code (None on timeout)."""
        return self.child.wait(timeout)

    def stop(self, *, timeout: float = 15.0) -> int:
        """Stop like Ctrl-C: SIGINT to launch, which stops its nodes; escalate if stuck."""
        if self.child.alive:
            with contextlib.suppress(ProcessLookupError):
                send(self.child.pid, signal.SIGINT, reason="stopping the launch (Ctrl-C)")
            if self.child.wait(timeout) is not None:
                self.child.stop(timeout=1.0)  # nothing left in the group
                return self.child.returncode  # type: ignore[return-value]
        return self.child.stop(timeout=2.0)


def _echo(handle: LaunchHandle, limit: int) -> Callable[[OutputLine], None]:
    count = 0

    def show(line: OutputLine) -> None:
        nonlocal count
        count += 1
        if count <= limit:
            print(line.text)
        if count == limit:
            print(f"... (more output: {handle!r}.output)")

    return show


def launch(
    package_or_path: str,
    file: str | None = None,
    *launch_args: str,
    session: Any = None,
    echo: int = 0,
    env: dict[str, str] | None = None,
) -> LaunchHandle:
    """Run `ros2 launch package_or_path [file] [name:=value ...]` in the background.

    Args:
        package_or_path: a package name, or the path of a launch file.
        file: the launch file in the package (omit it with a path).
        launch_args: `name:=value` launch arguments.
        session: the course session (default: this kernel's).
        echo: print the first `echo` output lines as they come.
        env: extra environment variables for the launch.
    """
    from ...session.session import get_session

    session = session or get_session()
    argv = [package_or_path, *([file] if file else []), *launch_args]
    command = [sys.executable, "-m", "course_lib.launch", "--noninteractive", *argv]
    child = session.spawn(command, name=f"ros2 launch {' '.join(argv)}", env_extra=env)
    handle = LaunchHandle(child, argv)
    if echo:
        child.add_listener(_echo(handle, echo))
    return handle
