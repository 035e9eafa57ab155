"""Run a launch description: visit actions, run processes and timers, shut down like launch."""

from __future__ import annotations

import asyncio
import signal
import sys
import traceback
from collections.abc import Callable, Iterable
from typing import Any

from ..core.context import LaunchContext
from ..core.event_handlers import OnShutdown
from ..core.events import Shutdown
from ..core.loading import LOADED_LAUNCH_FILES
from .process_runner import RunningProcess
from .screen import LaunchLog

__all__ = ["Runtime", "where_in_launch_file"]


def where_in_launch_file(exc: BaseException) -> tuple[str, int] | None:
    """Return (file, line) of a launch file where `exc` (or what caused it) was raised."""
    seen: set[int] = set()
    todo: list[BaseException] = [exc]
    while todo:
        error = todo.pop(0)
        if id(error) in seen:
            continue
        seen.add(id(error))
        if isinstance(error, SyntaxError) and error.filename and error.lineno:
            return error.filename, error.lineno
        frames = traceback.extract_tb(error.__traceback__)
        for frame in reversed(frames):
            if frame.filename in LOADED_LAUNCH_FILES and frame.lineno:
                return frame.filename, frame.lineno
        todo += list(getattr(error, "likely_errors", []))
        todo += [e for e in (error.__cause__, error.__context__) if e is not None]
    return None


class Runtime:
    """The launch service: one asyncio loop in the main thread."""

    def __init__(
        self,
        out: LaunchLog,
        *,
        argv: list[str],
        noninteractive: bool,
        on_line: Callable[[str, str, str], None] | None = None,
    ) -> None:
        self.out = out
        self.context = LaunchContext(argv=argv, noninteractive=noninteractive, runtime=self)
        self.processes: list[RunningProcess] = []
        self.shutting_down = False
        self.return_code = 0
        self._timers: list[tuple[asyncio.Task, bool]] = []
        self._wakeup: asyncio.Event | None = None
        self._sigint_seen = False
        self._cancelled = False
        self._line_listener = on_line
        self._sigint_pending = 0
        self._loop: asyncio.AbstractEventLoop | None = None

    def log(self, logger: str, level: str, message: str) -> None:
        """Log a launch message on the screen and in launch.log."""
        self.out.log(logger, level, message)

    def on_line(self, name: str, stream: str, line: str) -> None:
        """Pass a process's output line to the listener, if any."""
        if self._line_listener is not None:
            self._line_listener(name, stream, line)

    def wake(self) -> None:
        """Let the main loop re-check whether the launch is idle."""
        if self._wakeup is not None:
            self._wakeup.set()

    def start_process(self, action: Any, spec: Any) -> asyncio.Future:
        """Start a process (ExecuteProcess.execute); the future is done when it has ended."""
        running = RunningProcess(self, action, spec)
        self.processes.append(running)
        asyncio.get_running_loop().create_task(running.run())
        return running.finished

    def _running(self, action: Any) -> RunningProcess | None:
        return next((p for p in self.processes if p.action is action), None)

    def shutdown_process(self, action: Any, *, send_sigint: bool) -> None:
        """Stop the process of `action` like launch (called on the Shutdown event)."""
        running = self._running(action)
        if running is not None:
            running.shutdown(send_sigint=send_sigint)

    def signal_process(self, action: Any, name: str) -> None:
        """Send signal `name` to the process of `action` (a SignalProcess event)."""
        running = self._running(action)
        if running is not None:
            running.signal(name)

    def add_timer(self, period: float, actions: list[Any], cancel_on_shutdown: bool) -> None:
        """Visit `actions` after `period` seconds (called by TimerAction.execute)."""
        scope = dict(vars(self.context.locals))

        async def fire() -> None:
            await asyncio.sleep(period)
            if self.shutting_down and cancel_on_shutdown:
                return
            self.context.push_locals()
            self.context.extend_locals(scope)
            try:
                for action in actions:
                    self.visit_safely(action)
            finally:
                self.context.pop_locals()

        task = asyncio.get_running_loop().create_task(fire())
        task.add_done_callback(lambda _t: self.wake())
        self._timers.append((task, cancel_on_shutdown))

    async def sleep_unless_shutdown(self, seconds: float) -> None:
        """Sleep, returning early when the launch shuts down."""
        deadline = asyncio.get_running_loop().time() + seconds
        while not self.shutting_down and asyncio.get_running_loop().time() < deadline:
            await asyncio.sleep(min(0.05, seconds))

    def _visit(self, entity: Any) -> None:
        self.context.push_locals()
        try:
            for sub in entity.visit(self.context) or []:
                self._visit(sub)
        finally:
            self.context.pop_locals()

    def visit_safely(self, entity: Any) -> None:
        """Visit an entity; an exception is reported as launch does and shuts down."""
        try:
            self._visit(entity)
        except Exception as exc:
            self._report(exc)

    def _report(self, exc: Exception) -> None:
        message = f"Caught exception in launch (see debug for traceback): {exc}"
        self.log("launch", "ERROR", message)
        self.out.file(traceback.format_exc())
        where = where_in_launch_file(exc)
        if where is not None:
            print(f"Try: fix {where[0]}, line {where[1]} (course hint)", file=sys.stderr)
        self.return_code = 1
        self.request_shutdown(message)

    def _handle(self, handler: Any, event: Any) -> None:
        self.context.push_locals()
        try:
            entities = handler.handle(event, self.context)
            entities = list(entities) if isinstance(entities, Iterable) else [entities]
            for entity in entities:
                if entity is not None:
                    self._visit(entity)
        except Exception as exc:
            self._report(exc)
        finally:
            self.context.pop_locals()

    def process_events(self) -> None:
        """Handle the events queued so far (called before a process's exit is logged)."""
        self._process_events()

    def _process_events(self) -> None:
        """Handle queued events in order; each goes to every handler that matches it."""
        queue = self.context.event_queue
        while queue and not self._cancelled:
            event = queue.popleft()
            for handler in tuple(self.context.event_handlers):
                if handler.matches(event):
                    self._handle(handler, event)

    def request_shutdown(self, reason: str, *, due_to_sigint: bool = False) -> None:
        """Shut down as launch does: emit the Shutdown event (once); handlers stop things."""
        if not self.shutting_down:
            self.context.emit_event_sync(Shutdown(reason=reason, due_to_sigint=due_to_sigint))
        self.shutting_down = True
        self.context.is_shutdown = True
        self.wake()

    def _on_shutdown_event(self, event: Any, context: Any) -> None:
        self.shutting_down = True
        context.is_shutdown = True
        for task, cancel in self._timers:
            if cancel:
                task.cancel()

    def _raw_sigint(self, signum: int, frame: Any) -> None:
        # A Python-level handler runs at the next bytecode, before any output relayed after
        # it: launch's warning then always comes before what the interrupted nodes print.
        self._sigint_pending += 1
        if self._loop is not None:  # set before the handler is installed
            self._loop.call_soon_threadsafe(self.process_pending_signals)

    def process_pending_signals(self) -> None:
        """Handle SIGINTs received but not handled yet (called before relaying output)."""
        handled = bool(self._sigint_pending)
        while self._sigint_pending:
            self._sigint_pending -= 1
            self._on_sigint()
        if handled:  # launch's shutdown messages come before the output relayed after them
            self._process_events()

    def _on_sigint(self) -> None:
        base = "user interrupted with ctrl-c (SIGINT)"
        if self._sigint_seen:
            self.log("launch", "WARNING", f"{base} again, ignoring...")
            return
        self._sigint_seen = True
        self.log("launch", "WARNING", base)
        self.request_shutdown("ctrl-c (SIGINT)", due_to_sigint=True)

    def _on_sigterm(self, signum: int) -> None:
        name = signal.Signals(signum).name
        self.log("launch", "ERROR", f"user interrupted with ctrl-\\ ({name}), terminating...")
        self.log("launch", "ERROR", f"using {name} can result in orphaned processes")
        self.log("launch", "ERROR", "make sure no processes launched are still running")
        self._cancelled = True
        self.wake()

    def _busy(self) -> bool:
        self._timers = [(t, c) for t, c in self._timers if not t.done()]
        return any(not p.done for p in self.processes) or bool(self._timers)

    async def _loop_until_done(self) -> None:
        assert self._wakeup is not None
        while True:
            self._wakeup.clear()
            self._process_events()
            if self._cancelled:
                return
            if self.context.event_queue:
                continue
            if not self._busy():
                if self.shutting_down:
                    return
                self.request_shutdown("idle")
                continue
            await self._wakeup.wait()

    async def run(self, description: Any) -> int:
        """Run until every process has exited and no timer is pending; return the exit code."""
        loop = self._loop = asyncio.get_running_loop()
        self._wakeup = asyncio.Event()
        previous = signal.signal(signal.SIGINT, self._raw_sigint)
        for signum in (signal.SIGTERM, signal.SIGQUIT):
            loop.add_signal_handler(signum, self._on_sigterm, signum)
        self.context.register_event_handler(OnShutdown(on_shutdown=self._on_shutdown_event))
        try:
            self.log("launch", "INFO", f"All log files can be found below {self.out.run_dir}")
            self.log("launch", "INFO", "Default logging verbosity is set to INFO")
            self.visit_safely(description)
            await self._loop_until_done()
            if self._cancelled:
                self.log("launch", "ERROR", "run task was canceled")
                self.return_code = 1
            return self.return_code
        finally:
            signal.signal(signal.SIGINT, previous)
            for signum in (signal.SIGTERM, signal.SIGQUIT):
                loop.remove_signal_handler(signum)
