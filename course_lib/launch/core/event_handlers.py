"""Event handlers of `launch.event_handlers`: run entities when an event matches."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from .entity import Action, LaunchDescriptionEntity
from .event import BaseEventHandler, Event
from .events import ExecutionComplete, ProcessExited, ProcessIO, ProcessStarted, Shutdown

__all__ = [
    "EventHandler",
    "OnActionEventBase",
    "OnExecutionComplete",
    "OnProcessExit",
    "OnProcessIO",
    "OnProcessStart",
    "OnShutdown",
]


def _entity_list(entities: Any, argument: str) -> list[Any]:
    items = list(entities) if isinstance(entities, Iterable) else [entities]
    for item in items:
        if not isinstance(item, LaunchDescriptionEntity):
            raise TypeError(
                f"expected all items in '{argument}' iterable to be of type "
                f"'LaunchDescriptionEntity' but got '{type(item)}'"
            )
    return items


class EventHandler(BaseEventHandler):
    """Return fixed entities for every event the matcher accepts."""

    def __init__(
        self, *, matcher: Callable[[Event], bool], entities: Any = None, **kwargs: Any
    ) -> None:
        super().__init__(matcher=matcher, **kwargs)
        self.entities = entities

    def handle(self, event: Event, context: Any) -> Any:
        super().handle(event, context)
        return self.entities


class OnActionEventBase(BaseEventHandler):
    """Handle events of one class coming from one action (or any action, or a predicate)."""

    def __init__(
        self,
        *,
        action_matcher: Any,
        on_event: Any,
        target_event_cls: type[Event],
        argument: str,
        **kwargs: Any,
    ) -> None:
        if action_matcher is not None and not (
            isinstance(action_matcher, Action) or callable(action_matcher)
        ):
            raise TypeError("action_matcher must be an 'ExecuteProcess' instance or a callable")

        def matcher(event: Event) -> bool:
            if not isinstance(event, target_event_cls):
                return False
            if action_matcher is None:
                return True
            if isinstance(action_matcher, Action):
                return event.action is action_matcher  # type: ignore[attr-defined]
            return bool(action_matcher(event.action))  # type: ignore[attr-defined]

        super().__init__(matcher=matcher, **kwargs)
        self._call = on_event if callable(on_event) else None
        self._entities = [] if callable(on_event) else _entity_list(on_event, argument)

    def handle(self, event: Event, context: Any) -> Any:
        super().handle(event, context)
        if self._call is None:
            return self._entities
        return self._call(event, context)

    def describe(self) -> tuple[str, list[Any]]:
        return (type(self).__name__, list(self._entities))


class OnProcessStart(OnActionEventBase):
    """Run entities (or call `on_start(event, context)`) when a process starts."""

    def __init__(self, *, target_action: Any = None, on_start: Any, **kwargs: Any) -> None:
        super().__init__(
            action_matcher=target_action,
            on_event=on_start,
            target_event_cls=ProcessStarted,
            argument="on_start",
            **kwargs,
        )


class OnProcessExit(OnActionEventBase):
    """Run entities (or call `on_exit(event, context)`) when a process exits."""

    def __init__(self, *, target_action: Any = None, on_exit: Any, **kwargs: Any) -> None:
        super().__init__(
            action_matcher=target_action,
            on_event=on_exit,
            target_event_cls=ProcessExited,
            argument="on_exit",
            **kwargs,
        )


class OnExecutionComplete(OnActionEventBase):
    """Run entities (or call `on_completion(event, context)`) when an action completes."""

    def __init__(self, *, target_action: Any = None, on_completion: Any, **kwargs: Any) -> None:
        super().__init__(
            action_matcher=target_action,
            on_event=on_completion,
            target_event_cls=ExecutionComplete,
            argument="on_completion",
            **kwargs,
        )


class OnProcessIO(OnActionEventBase):
    """Call `on_stdout(event)` / `on_stderr(event)` with what a process writes."""

    def __init__(
        self,
        *,
        target_action: Any = None,
        on_stdin: Callable[[ProcessIO], Any] | None = None,
        on_stdout: Callable[[ProcessIO], Any] | None = None,
        on_stderr: Callable[[ProcessIO], Any] | None = None,
        **kwargs: Any,
    ) -> None:
        def handle(event: Any, _context: Any) -> Any:
            if event.from_stdout and on_stdout is not None:
                return on_stdout(event)
            if event.from_stderr and on_stderr is not None:
                return on_stderr(event)
            if event.from_stdin and on_stdin is not None:
                return on_stdin(event)
            return None

        super().__init__(
            action_matcher=target_action,
            on_event=handle,
            target_event_cls=ProcessIO,
            argument="on_event",
            **kwargs,
        )


class OnShutdown(BaseEventHandler):
    """Run entities (or call `on_shutdown(event, context)`) when the launch shuts down."""

    def __init__(self, *, on_shutdown: Any, **kwargs: Any) -> None:
        super().__init__(matcher=lambda event: isinstance(event, Shutdown), **kwargs)
        self._on_shutdown = on_shutdown

    def handle(self, event: Event, context: Any) -> Any:
        super().handle(event, context)
        if callable(self._on_shutdown):
            return self._on_shutdown(event, context)
        return self._on_shutdown
