"""Core of launch descriptions: entities, actions and the condition base class."""

from __future__ import annotations

from typing import Any

__all__ = ["Action", "Condition", "LaunchDescriptionEntity"]


class LaunchDescriptionEntity:
    """Anything a launch description may hold."""

    def visit(self, context: Any) -> list[Any] | None:
        """Apply this entity to the context; return the entities to visit next."""
        return None

    def describe_sub_entities(self) -> list[Any]:
        """Return the entities inside this one, known without a context."""
        return []

    def describe_conditional_sub_entities(self) -> list[Any]:
        """Return the entities that run only if something happens (an event, ...)."""
        return []


class Condition:
    """Decides at visit time whether an action runs."""

    def __init__(self, predicate: Any) -> None:
        self._predicate = predicate

    def evaluate(self, context: Any) -> bool:
        """Return whether the action should run."""
        return bool(self._predicate(context))


class Action(LaunchDescriptionEntity):
    """An action: runs `execute` when its condition (if any) holds."""

    def __init__(self, *, condition: Condition | None = None) -> None:
        self.condition = condition

    def visit(self, context: Any) -> list[Any] | None:
        if self.condition is None or self.condition.evaluate(context):
            try:
                return self.execute(context)
            finally:
                context.action_executed(self)
        return None

    def execute(self, context: Any) -> list[Any] | None:
        """Do what the action does; return entities to visit next."""
        return None

    def get_asyncio_future(self) -> Any:
        """Return a future done when the action completes (None: complete once executed)."""
        return None

    def describe(self) -> str:
        """Return a short description."""
        return f"{type(self).__name__}"
