"""Core of events: the event base class and the event handler base class."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["BaseEventHandler", "Event"]


class Event:
    """Something that happened in the launch (a process started, shutdown, ...)."""

    name = "launch.Event"

    def __repr__(self) -> str:
        return f"<{type(self).__name__}>"


class BaseEventHandler:
    """Matches events and returns the entities to visit for them."""

    def __init__(self, *, matcher: Callable[[Event], bool], handle_once: bool = False) -> None:
        self.matcher = matcher
        self.handle_once = handle_once

    def matches(self, event: Event) -> bool:
        """Return whether this handler handles `event`."""
        return bool(self.matcher(event))

    def handle(self, event: Event, context: Any) -> Any:
        """Handle `event`: make it `context.locals.event`; subclasses return entities."""
        context.extend_locals({"event": event})
        if self.handle_once:
            context.unregister_event_handler(self)
        return None

    def describe(self) -> tuple[str, list[Any]]:
        """Return a description and the entities known to be returned."""
        return (f"{type(self).__name__}", [])
