"""The launch context: configurations, locals and environment seen by actions."""

from __future__ import annotations

import asyncio
import os
from collections import deque
from types import SimpleNamespace
from typing import Any

from .event import BaseEventHandler, Event
from .events import ExecutionComplete

__all__ = ["LaunchContext"]


class LaunchContext:
    """What actions read and change while a launch description is visited."""

    def __init__(
        self, *, argv: list[str] | None = None, noninteractive: bool = False, runtime: Any = None
    ) -> None:
        self.argv = list(argv or [])
        self.noninteractive = noninteractive
        self.runtime = runtime  # None when only describing (show-args, dry run)
        self.launch_configurations: dict[str, str] = {}
        self._config_stack: list[dict[str, str]] = []
        self._locals_stack: list[dict[str, Any]] = [{}]
        self.environment: dict[str, str] = dict(os.environ)
        self.initial_environment = dict(self.environment)  # what ResetEnvironment restores
        self._env_stack: list[dict[str, str]] = []
        self.is_shutdown = False
        self.node_names: list[str] = []
        self.process_counter = 0
        self.event_handlers: deque[BaseEventHandler] = deque()  # newest first, as launch
        self.event_queue: deque[Event] = deque()
        self.planned_processes: list[Any] = []  # processes found when only describing
        self.messages: list[tuple[str, str, str]] = []  # (logger, level, text) when describing
        self.code_run: list[str] = []  # the Python expressions and commands reading it ran

    @property
    def locals(self) -> SimpleNamespace:
        """Return the locals of the current scope (file path, ros arguments, ...)."""
        merged: dict[str, Any] = {}
        for scope in self._locals_stack:
            merged.update(scope)
        return _Locals(merged)

    def extend_locals(self, values: dict[str, Any]) -> None:
        """Add values to the current scope's locals."""
        self._locals_stack[-1].update(values)

    def push_locals(self) -> None:
        """Start a new scope of locals."""
        self._locals_stack.append({})

    def pop_locals(self) -> None:
        """Drop the innermost scope of locals."""
        if len(self._locals_stack) > 1:
            self._locals_stack.pop()

    def push_launch_configurations(self) -> None:
        """Save launch configurations (a group scopes them)."""
        self._config_stack.append(dict(self.launch_configurations))

    def pop_launch_configurations(self) -> None:
        """Restore the launch configurations saved last."""
        self.launch_configurations = self._config_stack.pop()

    def push_environment(self) -> None:
        """Save the environment (a group scopes it)."""
        self._env_stack.append(dict(self.environment))

    def pop_environment(self) -> None:
        """Restore the environment saved last."""
        self.environment = self._env_stack.pop()

    def register_event_handler(self, handler: BaseEventHandler, append: bool = False) -> None:
        """Register an event handler (before the others, unless `append`)."""
        if append:
            self.event_handlers.append(handler)
        else:
            self.event_handlers.appendleft(handler)

    def unregister_event_handler(self, handler: BaseEventHandler) -> None:
        """Unregister an event handler."""
        self.event_handlers.remove(handler)

    def would_handle_event(self, event: Event) -> bool:
        """Return whether any registered handler matches `event`."""
        return any(handler.matches(event) for handler in self.event_handlers)

    def emit_event_sync(self, event: Event) -> None:
        """Queue an event; the runtime handles it in order (describing only: it is kept)."""
        self.event_queue.append(event)
        if self.runtime is not None:
            self.runtime.wake()

    async def emit_event(self, event: Event) -> None:
        """Queue an event (the coroutine form launch also has)."""
        self.emit_event_sync(event)

    def action_executed(self, action: Any) -> None:
        """Emit ExecutionComplete for `action` once it completes, if anything handles it."""
        event = ExecutionComplete(action=action)
        if not self.would_handle_event(event):
            return
        future: asyncio.Future | None = action.get_asyncio_future()
        if future is None:
            self.emit_event_sync(event)
        else:
            future.add_done_callback(lambda _future: self.emit_event_sync(event))

    def log(self, logger: str, level: str, text: str) -> None:
        """Log as launch does (`[LEVEL] [logger]: text`), or keep it when only describing."""
        if self.runtime is not None:
            self.runtime.log(logger, level, text)
        else:
            self.messages.append((logger, level, text))

    def perform_substitution(self, substitution: Any) -> str:
        """Perform one substitution in this context."""
        return substitution.perform(self)


class _Locals(SimpleNamespace):
    """Locals readable as attributes and by key."""

    def __init__(self, values: dict[str, Any]) -> None:
        super().__init__(**values)

    def __getitem__(self, key: str) -> Any:
        return self.__dict__[key]

    def __contains__(self, key: object) -> bool:
        return key in self.__dict__
