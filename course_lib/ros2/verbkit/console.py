"""Where a running `ros2` verb writes: collected for cells and the API, streamed for terminals."""

from __future__ import annotations

import threading
from collections.abc import Callable

from ..results import CommandOutput

__all__ = ["CollectingConsole", "Console", "StreamingConsole"]


class Console:
    """Output of one command, plus the flag that asks a streaming verb to stop."""

    def __init__(self, *, width: int = 80) -> None:
        self.width = width
        self.cancelled = threading.Event()

    def out(self, text: str) -> None:
        """Write text to the command's stdout."""
        raise NotImplementedError

    def err(self, text: str) -> None:
        """Write text to the command's stderr."""
        raise NotImplementedError

    def emit(self, output: CommandOutput) -> int:
        """Write a rendered result; return its exit code."""
        if output.stdout:
            self.out(output.stdout)
        if output.stderr:
            self.err(output.stderr)
        return output.exit_code


class CollectingConsole(Console):
    """Keep everything written, in order, for a CommandOutput."""

    def __init__(self, *, width: int = 80) -> None:
        super().__init__(width=width)
        self.chunks: list[tuple[str, str]] = []
        self._lock = threading.Lock()

    def out(self, text: str) -> None:
        with self._lock:
            self.chunks.append(("stdout", text))

    def err(self, text: str) -> None:
        with self._lock:
            self.chunks.append(("stderr", text))

    def result(self, exit_code: int) -> CommandOutput:
        """Return what was written with the given exit code."""
        with self._lock:
            out = "".join(t for s, t in self.chunks if s == "stdout")
            err = "".join(t for s, t in self.chunks if s == "stderr")
        return CommandOutput(out, err, exit_code)


class StreamingConsole(Console):
    """Pass every write on at once (to a socket or a terminal)."""

    def __init__(self, write: Callable[[str, str], None], *, width: int = 80) -> None:
        super().__init__(width=width)
        self._write = write

    def out(self, text: str) -> None:
        self._write("stdout", text)

    def err(self, text: str) -> None:
        self._write("stderr", text)
