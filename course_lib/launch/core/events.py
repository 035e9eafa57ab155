"""Events of `launch.events` and `launch.events.process`, as the runtime emits them."""

from __future__ import annotations

from typing import Any

from .event import Event

__all__ = [
    "ExecutionComplete",
    "ProcessExited",
    "ProcessIO",
    "ProcessStarted",
    "ProcessStderr",
    "ProcessStdout",
    "RunningProcessEvent",
    "Shutdown",
    "SignalProcess",
]


class Shutdown(Event):
    """The launch is shutting down (idle, Ctrl-C, an error or a `Shutdown` action)."""

    name = "launch.events.Shutdown"

    def __init__(self, *, reason: str = "reason not given", due_to_sigint: bool = False) -> None:
        self.reason = reason
        self.due_to_sigint = due_to_sigint


class ExecutionComplete(Event):
    """An action has completed (a process action: once its process has exited)."""

    name = "launch.events.ExecutionComplete"

    def __init__(self, *, action: Any) -> None:
        self.action = action


class RunningProcessEvent(Event):
    """Something about a running process: its action, unique name, command and pid."""

    name = "launch.events.process.RunningProcessEvent"

    def __init__(
        self,
        *,
        action: Any,
        name: str,
        cmd: list[str],
        cwd: str | None,
        env: dict[str, str] | None,
        pid: int,
    ) -> None:
        self.action = action
        self.process_name = name
        self.cmd = cmd
        self.cwd = cwd
        self.env = env
        self.pid = pid

    @property
    def execute_process_action(self) -> Any:
        """Return the ExecuteProcess action (launch's other name for `action`)."""
        return self.action


class ProcessStarted(RunningProcessEvent):
    """A process has started."""

    name = "launch.events.process.ProcessStarted"


class ProcessExited(RunningProcessEvent):
    """A process has exited, with `returncode`."""

    name = "launch.events.process.ProcessExited"

    def __init__(self, *, returncode: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.returncode = returncode


class ProcessIO(RunningProcessEvent):
    """A process wrote `text` (bytes, as read) on `fd` (1 stdout, 2 stderr)."""

    name = "launch.events.process.ProcessIO"

    def __init__(self, *, text: bytes, fd: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.text = text
        self.fd = fd

    @property
    def from_stdin(self) -> bool:
        return self.fd == 0

    @property
    def from_stdout(self) -> bool:
        return self.fd == 1

    @property
    def from_stderr(self) -> bool:
        return self.fd == 2


class ProcessStdout(ProcessIO):
    """A process wrote on stdout."""

    name = "launch.events.process.ProcessStdout"

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(fd=1, **kwargs)


class ProcessStderr(ProcessIO):
    """A process wrote on stderr."""

    name = "launch.events.process.ProcessStderr"

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(fd=2, **kwargs)


class SignalProcess(Event):
    """Send a signal (by name, e.g. 'SIGINT') to the process of `action`."""

    name = "launch.events.process.SignalProcess"

    def __init__(self, *, action: Any, signal_name: str) -> None:
        self.action = action
        self.signal_name = signal_name
