"""The `ros2` verbs as Python functions returning structured results (widgets, plots, checks)."""

from __future__ import annotations

import queue
import shlex
from collections.abc import Sequence
from typing import Any

from ..command.commands import run_collected
from ..node.session_client import client
from ..paramfile import ParamFileError, read_param_file
from ..render import dump_tree
from ..results import CommandOutput, Descriptor, NodeInfo, SetResult, TopicInfo
from ..values import NOT_SET, ParamValue
from .errors import NodeNotFoundError, ParameterNotSetError, TopicNotFoundError

__all__ = [
    "ParamFileError",
    "client",
    "node_info",
    "node_list",
    "param_delete",
    "param_describe",
    "param_dump",
    "param_get",
    "param_list",
    "param_load",
    "param_set",
    "ros2",
    "topic_echo_once",
    "topic_list",
]


def ros2(command: str | Sequence[str], *, cwd: str | None = None) -> CommandOutput:
    """Run a `ros2 ...` command line in this process; return its text and exit code."""
    argv = shlex.split(command) if isinstance(command, str) else list(command)
    if argv and argv[0] == "ros2":
        argv = argv[1:]
    return run_collected(argv, client_factory=client, cwd=cwd)


def _node(name: str) -> str:
    full = name if name.startswith("/") else "/" + name
    c = client()
    if not c.wait_for_node(full, include_hidden=True, timeout=0):
        raise NodeNotFoundError(full, [n.full_name for n in c.node_names()])
    return full


def node_list(*, include_hidden: bool = False) -> list[str]:
    """Return the running nodes' full names, sorted."""
    c = client()
    c.settle()
    return sorted(n.full_name for n in c.node_names(include_hidden=include_hidden))


def node_info(node: str) -> NodeInfo:
    """Return a node's publishers, subscribers, services and actions."""
    return client().node_info(_node(node))


def topic_list(*, include_hidden: bool = False) -> list[TopicInfo]:
    """Return the topics with their types."""
    c = client()
    c.settle()
    return c.topics(include_hidden=include_hidden)


def param_list(node: str) -> list[str]:
    """Return the names of a node's parameters, sorted."""
    return sorted(client().list_parameters(_node(node)))


def param_get(node: str, name: str) -> ParamValue:
    """Return one parameter's value with its ROS type."""
    full = _node(node)
    values = client().get_parameters(full, [name])
    if not values or values[0].type == NOT_SET:
        raise ParameterNotSetError(full, name, param_list(full))
    return values[0]


def param_set(node: str, name: str, value: Any) -> SetResult:
    """Set a parameter to a Python value (0.2 is a double, 1 an integer); return the result."""
    full = _node(node)
    (result,) = client().set_parameters(full, [(name, ParamValue.of(value))])
    return result


def param_delete(node: str, name: str) -> SetResult:
    """Undeclare a parameter (nodes refuse this for statically declared ones)."""
    full = _node(node)
    (result,) = client().set_parameters(full, [(name, ParamValue(NOT_SET))])
    return result


def param_describe(node: str, *names: str) -> list[Descriptor]:
    """Return the descriptors of the named parameters (all of them when no name is given)."""
    full = _node(node)
    c = client()
    return c.describe_parameters(full, list(names) or sorted(c.list_parameters(full)))


def param_dump(node: str) -> dict[str, Any]:
    """Return the mapping `ros2 param dump` prints (dotted names nested)."""
    full = _node(node)
    c = client()
    names = sorted(c.list_parameters(full))
    return dump_tree(full, zip(names, c.get_parameters(full, names), strict=False))


def param_load(node: str, path: str, *, use_wildcard: bool = True) -> list[SetResult]:
    """Apply a parameter file to a running node; raise ParamFileError if the file is bad."""
    full = _node(node)
    values = read_param_file(path, use_wildcard=use_wildcard, target_node=full)
    return client().set_parameters(full, values) if values else []


def topic_echo_once(topic: str, *, timeout: float = 5.0) -> Any:
    """Return the next message published on `topic` (a ROS message object)."""
    from ..verbkit.console import CollectingConsole
    from ..verbkit.context import Context
    from ..verbkit.topic_types import expand_topic, message_class, type_of

    ctx = Context(CollectingConsole(), client)
    type_name = type_of(ctx, topic)
    if type_name is None:
        raise TopicNotFoundError(
            f"No topic {topic} in the graph",
            hint="check `ros2 topic list`; is the node publishing it running?",
        )
    inbox: queue.Queue[Any] = queue.Queue()
    node = client().node
    sub = node.create_subscription(message_class(type_name), expand_topic(topic), inbox.put, 10)
    try:
        return inbox.get(timeout=timeout)
    except queue.Empty:
        raise TopicNotFoundError(
            f"No message on {topic} within {timeout:g} s", hint="is the publisher running?"
        ) from None
    finally:
        node.destroy_subscription(sub)
