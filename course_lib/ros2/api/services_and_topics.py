"""The service, topic and interface verbs as Python functions returning structured results."""

from __future__ import annotations

from typing import Any

from .errors import TopicNotFoundError

__all__ = [
    "call_service",
    "interface_show",
    "service_list",
    "service_type",
    "topic_info",
    "topic_publish",
]


def service_list(*, include_hidden: bool = False) -> list[tuple[str, list[str]]]:
    """Return the services with their types, as `ros2 service list -t` shows them."""
    from ..node.graph import services
    from .nodes_and_params import client

    c = client()
    c.settle()
    return services(c, include_hidden=include_hidden)


def service_type(service: str) -> str:
    """Return a service's type; raise TopicNotFoundError if no node offers it."""
    from ..node.graph import types_of
    from .nodes_and_params import client

    types = types_of(client(), service, kind="service")
    if not types:
        raise TopicNotFoundError(
            f"No service {service} in the graph", hint="check `ros2 service list`"
        )
    return types[0]


def call_service(
    service: str, srv_type: str, values: dict | None = None, *, timeout: float = 10.0
) -> Any:
    """Call a service once with a request filled from `values`; return the response message."""
    from ...core.waiting import wait_until
    from ..msgfill import set_message_fields
    from ..verbs.service_call import service_class
    from .nodes_and_params import client

    srv = service_class(srv_type)
    request = srv.Request()
    set_message_fields(request, values or {})
    c = client()
    cli = c.node.create_client(srv, service)
    try:
        if not wait_until(cli.service_is_ready, timeout):
            raise TopicNotFoundError(
                f"No server for {service} within {timeout:g} s",
                hint="check `ros2 service list`; is its node running?",
            )
        from ...session.session import get_session

        return get_session().wait_future(cli.call_async(request), timeout)
    finally:
        c.node.destroy_client(cli)


def topic_info(topic: str) -> dict[str, Any]:
    """Return a topic's types and its publisher and subscription counts."""
    from ..node.graph import types_of
    from .nodes_and_params import client

    c = client()
    node = c.node
    types = types_of(c, topic)
    if types is None:
        raise TopicNotFoundError(f"No topic {topic} in the graph", hint="check `ros2 topic list`")
    return {
        "types": list(types),
        "publishers": node.count_publishers(topic),
        "subscriptions": node.count_subscribers(topic),
    }


def topic_publish(
    topic: str, msg_type: str, values: dict | None = None, *, wait: float = 5.0
) -> Any:
    """Publish one message (after waiting up to `wait` s for a subscriber); return it."""
    from ...core.waiting import wait_until
    from ..msgfill import import_type, set_message_fields
    from ..node.delivery import keep_until_acknowledged
    from .nodes_and_params import client

    msg_class = import_type(msg_type, "msg")
    msg = msg_class()
    set_message_fields(msg, values or {}, expand_header_auto=True, expand_time_now=True)
    node = client().node
    pub = node.create_publisher(msg_class, topic, 10)
    try:
        wait_until(lambda: pub.get_subscription_count() > 0, wait)
        pub.publish(msg)
        keep_until_acknowledged(pub, keep_alive=0.1)  # ros2topic's keep-alive, and delivery
        return msg
    finally:
        node.destroy_publisher(pub)


def interface_show(name: str, *, comments: bool = True) -> str:
    """Return the text `ros2 interface show` prints for `pkg/msg/Name` (no ROS needed)."""
    from ...core import ament
    from ..interface_index import interface_path, prefixes
    from ..interface_text import show_lines

    roots = prefixes(ament.workspace_env())
    lines = show_lines(name, lambda n: interface_path(n, roots).read_text(), comments=comments)
    return "".join(f"{line}\n" for line in lines)
