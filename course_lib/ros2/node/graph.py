"""Graph look-ups shared by the service and topic verbs, over the session's client node."""

from __future__ import annotations

from typing import Any

from .graph_client import YOUNG_CLIENT_S

__all__ = ["lookup", "own_prefix", "services", "topics", "types_of"]


def own_prefix(client: Any) -> str:
    """Return `/<client node>/`: the course's own node is not part of what the learner sees."""
    node = client.node
    namespace = node.get_namespace().rstrip("/")
    return f"{namespace}/{node.get_name()}/"


def services(client: Any, *, include_hidden: bool) -> list[tuple[str, list[str]]]:
    """Return (service, types) pairs in the graph's order, as ros2service lists them."""
    from rclpy.topic_or_service_is_hidden import topic_or_service_is_hidden

    mine = own_prefix(client)
    return [
        (name, list(types))
        for name, types in client.node.get_service_names_and_types()
        if not name.startswith(mine) and (include_hidden or not topic_or_service_is_hidden(name))
    ]


def topics(client: Any, *, include_hidden: bool) -> list[tuple[str, list[str]]]:
    """Return (topic, types) pairs in the graph's order, as ros2topic lists them."""
    return [(t.name, list(t.types)) for t in client.topics(include_hidden=include_hidden)]


def types_of(
    client: Any, name: str, *, kind: str = "topic", include_hidden: bool = True
) -> list[str] | None:
    """Return the types of topic (or service, `kind="service"`) `name`, or None if the graph
    has none of that name; a young client waits for discovery first (`lookup`)."""
    listing = services if kind == "service" else topics
    found: list[str] | None = lookup(
        client, lambda: dict(listing(client, include_hidden=include_hidden)).get(name)
    )
    return found


def lookup(client: Any, find: Any) -> Any:
    """Return find()'s first non-None answer; a young client waits for discovery first, until
    its graph is known whole (RosClient.wait_for: then a miss is an answer) or it is warm."""
    found: list[Any] = []

    def look() -> bool:
        answer = find()
        if answer is not None:
            found.append(answer)
        return answer is not None

    client.wait_joined()  # a node starting now: count all of it, not what arrived so far
    young = YOUNG_CLIENT_S - client.age()
    if young > 0:
        client.wait_for(look, timeout=0, limit=young)
    else:
        look()
    return found[0] if found else None
