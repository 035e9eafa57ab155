"""The `ros2 node`, `ros2 topic list` and `ros2 param` verbs: ask the graph, render, print."""

from __future__ import annotations

import argparse
from typing import Any

from .. import render
from ..node.discovery import requested_spin_time
from ..paramfile import ParamFileError, read_param_file
from ..results import ParamListing, node_name_of
from ..values import NOT_SET, ParamValue, parse_value
from .context import Context

__all__ = [
    "node_info",
    "node_list",
    "param_delete",
    "param_describe",
    "param_dump",
    "param_get",
    "param_list",
    "param_load",
    "param_set",
    "topic_list",
]

NODE_NOT_FOUND = "Node not found"
LIST_SERVICE_WAIT_S = 2.0


def _absolute(name: str) -> str:
    return name if name.startswith("/") else "/" + name


class SimTimeUnavailable(RuntimeError):
    """`--use-sim-time` asked of a door whose shared node runs on wall time."""

    cli_message = (
        "--use-sim-time needs a node of this command's own: run the command in a terminal "
        "(a JupyterLab terminal, or `!ros2 ...` in a cell); the cells' `%ros2` commands "
        "share one node on wall time."
    )


def _settled(args: argparse.Namespace, ctx: Context) -> Any:
    """Return the client once it has discovered the whole graph (`--spin-time` at least)."""
    client = ctx.client
    if getattr(args, "use_sim_time", False) and not client.uses_sim_time:
        raise SimTimeUnavailable()
    client.settle(min_age_s=requested_spin_time(args))
    return client


def _find_node(args: argparse.Namespace, ctx: Context) -> str | None:
    """Return the node's absolute name once the graph shows it, else None."""
    name = _absolute(args.node_name)
    found = ctx.client.wait_for_node(
        name, include_hidden=args.include_hidden_nodes, timeout=args.timeout
    )
    return name if found else None


def node_list(args: argparse.Namespace, ctx: Context) -> int:
    """`ros2 node list [-a] [-c]`."""
    names = _settled(args, ctx).node_names(include_hidden=args.all)
    if not names and not args.count_nodes:
        return 0
    return ctx.console.emit(
        render.node_list([n.full_name for n in names], count_only=args.count_nodes)
    )


def node_info(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 node info <node>`."""
    client = _settled(args, ctx)

    def count() -> int:
        names = client.node_names(include_hidden=args.include_hidden)
        return [n.full_name for n in names].count(args.node_name)

    if count() == 0 and args.node_name.startswith("/"):
        client.wait_for_node(args.node_name, include_hidden=args.include_hidden, timeout=0)
    duplicates = count()
    if duplicates == 0:
        return f"Unable to find node '{args.node_name}'"
    info = client.node_info(args.node_name, include_hidden=args.include_hidden)
    return ctx.console.emit(render.node_info(info, duplicates=duplicates))


def topic_list(args: argparse.Namespace, ctx: Context) -> int:
    """`ros2 topic list [-t] [-c] [-v]`."""
    client = _settled(args, ctx)
    topics = client.topics(include_hidden=args.include_hidden_topics)
    if args.count_topics:
        return ctx.console.emit(render.topic_list(topics, count_only=True))
    if not topics:
        return 0
    if args.verbose:
        node = client.node
        for publishers in (True, False):
            lines = ["Published topics:" if publishers else "Subscribed topics:"]
            for topic in topics:
                n = (node.count_publishers if publishers else node.count_subscribers)(topic.name)
                if n:
                    kind = "publisher" if publishers else "subscriber"
                    lines.append(
                        f" * {topic.name} [{', '.join(topic.types)}] {n} {kind}"
                        + ("s" if n > 1 else "")
                    )
            ctx.console.out("\n".join(lines) + "\n\n")
        return 0
    return ctx.console.emit(render.topic_list(topics, show_types=args.show_types))


def _listing(ctx: Context, node: Any, args: argparse.Namespace, wait: float) -> ParamListing:
    client = ctx.client
    if not client.services_ready(node.full_name, timeout=wait):
        return ParamListing(node)
    names = client.list_parameters(node.full_name, args.param_prefixes)
    types: dict[str, int] = {}
    if args.param_type and names:
        types = {d.name: d.type for d in client.describe_parameters(node.full_name, names)}
    return ParamListing(node, tuple(names), types)


def param_list(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param list [node] [--filter R] [--param-prefixes P..] [--param-type]`."""
    client = _settled(args, ctx)
    nodes = client.node_names(include_hidden=args.include_hidden_nodes)
    if args.node_name:
        name = _absolute(args.node_name)
        if name not in {n.full_name for n in nodes}:
            if not client.wait_for_node(name, include_hidden=args.include_hidden_nodes, timeout=0):
                return NODE_NOT_FOUND
            nodes = client.node_names(include_hidden=args.include_hidden_nodes)
        nodes = [n for n in nodes if n.full_name == name]
    wait = 5.0 if args.node_name else LIST_SERVICE_WAIT_S
    listings = [_listing(ctx, node, args, wait) for node in nodes]
    regex = args.filter[0] if args.filter else None
    return ctx.console.emit(
        render.param_list(
            listings, single_node=bool(args.node_name), regex=regex, with_types=args.param_type
        )
    )


def param_get(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param get <node> <name> [--hide-type]`."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    values = ctx.client.get_parameters(node, [args.parameter_name])
    return ctx.console.emit(
        render.param_get(values[0] if values else None, hide_type=args.hide_type)
    )


def param_set(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param set <node> <name> <value>` (value typed by YAML rules, never converted)."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    value = parse_value(args.value)
    (result,) = ctx.client.set_parameters(node, [(args.parameter_name, value)])
    return ctx.console.emit(render.param_set(result))


def param_delete(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param delete <node> <name>`."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    (result,) = ctx.client.set_parameters(node, [(args.parameter_name, ParamValue(NOT_SET))])
    return ctx.console.emit(render.param_delete(result))


def param_describe(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param describe <node> <name> [<name> ...]`."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    descriptors = ctx.client.describe_parameters(node, args.parameter_names)
    return ctx.console.emit(render.param_describe(descriptors))


def param_dump(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param dump <node>`: the node's parameters as YAML on stdout."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    full_name = node_name_of(node).full_name
    client = ctx.client
    if not client.services_ready(node):
        ctx.console.err(
            f"Wait for service timed out waiting for parameter services for node {full_name}\n"
        )
        return 0
    names = sorted(client.list_parameters(node))
    values = client.get_parameters(node, names)
    return ctx.console.emit(render.param_dump(full_name, zip(names, values, strict=False)))


def param_load(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param load <node> <file> [--no-use-wildcard]`; a bad file changes nothing."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    if not ctx.client.services_ready(node):
        return f"Wait for service timed out waiting for parameter services for node {node}"
    try:
        values = read_param_file(
            args.parameter_file,
            use_wildcard=not args.no_use_wildcard,
            target_node=node,
            cwd=ctx.cwd,
        )
    except ParamFileError as exc:
        return ctx.console.emit(exc.output)
    results = ctx.client.set_parameters(node, values) if values else []
    return ctx.console.emit(render.param_load(results))
