"""Actions about events: emit one, (un)register a handler, shut the launch down."""

from __future__ import annotations

from typing import Any

from ..core.entity import Action
from ..core.event import BaseEventHandler, Event
from ..core.events import ProcessExited
from ..core.events import Shutdown as ShutdownEvent
from .exposure import expose, expose_action

__all__ = ["EmitEvent", "RegisterEventHandler", "Shutdown", "UnregisterEventHandler"]


@expose("launch.actions")
class EmitEvent(Action):
    """Emit an event (e.g. `launch.events.Shutdown(reason=...)`)."""

    def __init__(self, *, event: Event, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if not isinstance(event, Event):
            raise RuntimeError(f"EmitEvent() expected an event instance, got '{event}'.")
        self.event = event

    def execute(self, context: Any) -> None:
        context.emit_event_sync(self.event)


@expose("launch.actions")
class RegisterEventHandler(Action):
    """Register an event handler (`OnProcessStart(...)`, `OnShutdown(...)`, ...)."""

    def __init__(self, event_handler: BaseEventHandler, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.event_handler = event_handler

    def execute(self, context: Any) -> None:
        context.register_event_handler(self.event_handler)

    def describe_conditional_sub_entities(self) -> list[Any]:
        return list(self.event_handler.describe()[1])


@expose("launch.actions")
class UnregisterEventHandler(Action):
    """Unregister an event handler registered before."""

    def __init__(self, event_handler: BaseEventHandler, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.event_handler = event_handler

    def execute(self, context: Any) -> None:
        context.unregister_event_handler(self.event_handler)


@expose_action("shutdown")
class Shutdown(EmitEvent):
    """Shut the whole launch down (saying so when a required process has exited)."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<shutdown reason=/>`."""
        return cls(reason=entity.get_attr("reason", optional=True) or "reason not given")

    def __init__(self, *, reason: Any = "reason not given", **kwargs: Any) -> None:
        super().__init__(event=ShutdownEvent(reason=reason), **kwargs)

    def execute(self, context: Any) -> None:
        event = getattr(context.locals, "event", None)
        if isinstance(event, ProcessExited):
            context.log(
                "launch",
                "INFO",
                f"process[{event.process_name}] was required: shutting down launched system",
            )
        super().execute(context)
