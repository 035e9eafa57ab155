"""A topic's name and type as the `ros2 topic` verbs read them: the full name, the one type in
the graph, the message class."""

from __future__ import annotations

import importlib
from typing import Any

from .context import Context

__all__ = ["expand_topic", "import_message", "message_class", "type_of"]


def expand_topic(topic: str) -> str:
    """Return the topic's full name, as ros2cli expands it (`chatter` -> `/chatter`)."""
    from rclpy.expand_topic_name import expand_topic_name

    return expand_topic_name(topic, "ros2cli", "/")


def type_of(ctx: Context, topic: str, *, wait: bool = True) -> str | None:
    """Return the topic's one type (None if the graph has no such topic). With `wait`, a
    young client first gives discovery its time; a graph known whole that lacks the topic
    answers at once, as "Node not found" does (RosClient.wait_for)."""
    name = expand_topic(topic)
    found: list[str] = []

    def look() -> bool:
        for n, types in ctx.client.topics(include_hidden=True):
            if n == name:
                if len(types) > 1:
                    raise RuntimeError(
                        f"Cannot echo topic '{topic}', as it contains more than one type: "
                        f"[{', '.join(types)}]"
                    )
                found.append(types[0])
                return True
        return False

    if wait:
        ctx.client.wait_for(look, timeout=0)
    else:
        look()
    return found[0] if found else None


def message_class(type_name: str) -> Any:
    """Return the class of `pkg/msg/Name`; raise the import's own error if it is not here."""
    package, kind, name = type_name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), name)


def import_message(type_name: str) -> Any:
    """Return the class of a topic's type, or raise ros2topic's error if it cannot be
    imported here (a package this environment lacks)."""
    try:
        return message_class(type_name)
    except (AttributeError, ModuleNotFoundError, ValueError):
        raise RuntimeError(f"The message type '{type_name}' is invalid") from None
