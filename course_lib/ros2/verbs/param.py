"""`ros2 param list|get|set|describe|dump|load|delete`: the arguments and the handlers."""

from __future__ import annotations

import argparse
import os
from typing import Any

from ...core.param_journal import acting_door, current_door
from .. import render
from ..paramfile import ParamFileError, read_param_file
from ..results import ParamListing, node_name_of
from ..values import NOT_SET, ParamValue, parse_value
from ..verbkit import options
from ..verbkit.context import Context, settled_client
from ..verbkit.registry import command, verb

__all__ = [
    "param_delete",
    "param_delete_arguments",
    "param_describe",
    "param_describe_arguments",
    "param_dump",
    "param_dump_arguments",
    "param_get",
    "param_get_arguments",
    "param_list",
    "param_list_arguments",
    "param_load",
    "param_load_arguments",
    "param_set",
    "param_set_arguments",
]

Parser = argparse.ArgumentParser

NODE_NOT_FOUND = "Node not found"
LIST_SERVICE_WAIT_S = 2.0


command("param", "Various param related sub-commands")


def _absolute(name: str) -> str:
    return name if name.startswith("/") else "/" + name


def _find_node(args: argparse.Namespace, ctx: Context) -> str | None:
    """Return the node's absolute name once the graph shows it, else None."""
    name = _absolute(args.node_name)
    found = ctx.client.wait_for_node(
        name, include_hidden=args.include_hidden_nodes, timeout=args.timeout
    )
    return name if found else None


def _listing(ctx: Context, node: Any, args: argparse.Namespace, wait: float) -> ParamListing:
    client = ctx.client
    if not client.services_ready(node.full_name, timeout=wait):
        return ParamListing(node)
    names = client.list_parameters(node.full_name, args.param_prefixes)
    types: dict[str, int] = {}
    if args.param_type and names:
        types = {d.name: d.type for d in client.describe_parameters(node.full_name, names)}
    return ParamListing(node, tuple(names), types)


def param_list_arguments(parser: Parser) -> None:
    """Arguments of `ros2 param list`."""
    options.strategy(parser)
    parser.add_argument("node_name", nargs="?", help="Name of the ROS node")
    parser.add_argument(
        "--filter",
        nargs=1,
        help="Only parameters matching the regex expression will be showed. Supports `re` "
        "regex syntax.",
    )
    parser.add_argument(
        "--include-hidden-nodes", action="store_true", help="Consider hidden nodes as well"
    )
    parser.add_argument(
        "--param-prefixes",
        nargs="+",
        default=[],
        help="Only list parameters with the provided prefixes",
    )
    parser.add_argument(
        "--param-type", action="store_true", help="Print parameter types with parameter names"
    )


@verb("param", "list", "Output a list of available parameters", arguments=param_list_arguments)
def param_list(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param list [node] [--filter R] [--param-prefixes P..] [--param-type]`."""
    client = settled_client(args, ctx)
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


def param_get_arguments(parser: Parser) -> None:
    """Arguments of `ros2 param get`."""
    options.node_and_hidden(parser)
    parser.add_argument("parameter_name", help="Name of the parameter")
    parser.add_argument("--hide-type", action="store_true", help="Hide the type information")
    options.timeout(parser)


@verb("param", "get", "Get parameter", arguments=param_get_arguments)
def param_get(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param get <node> <name> [--hide-type]`."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    values = ctx.client.get_parameters(node, [args.parameter_name])
    return ctx.console.emit(
        render.param_get(values[0] if values else None, hide_type=args.hide_type)
    )


def param_set_arguments(parser: Parser) -> None:
    """Arguments of `ros2 param set`."""
    options.node_and_hidden(parser)
    parser.add_argument("parameter_name", help="Name of the parameter")
    parser.add_argument("value", help="Value of the parameter")
    options.timeout(parser)


@verb("param", "set", "Set parameter", arguments=param_set_arguments)
def param_set(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param set <node> <name> <value>` (value typed by YAML rules, never converted)."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    value = parse_value(args.value)
    (result,) = ctx.client.set_parameters(node, [(args.parameter_name, value)])
    return ctx.console.emit(render.param_set(result))


def param_delete_arguments(parser: Parser) -> None:
    """Arguments of `ros2 param delete`."""
    options.node_and_hidden(parser)
    parser.add_argument("parameter_name", help="Name of the parameter")
    options.timeout(parser)


@verb("param", "delete", "Delete parameter", arguments=param_delete_arguments)
def param_delete(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param delete <node> <name>`."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    (result,) = ctx.client.set_parameters(node, [(args.parameter_name, ParamValue(NOT_SET))])
    return ctx.console.emit(render.param_delete(result))


def param_describe_arguments(parser: Parser) -> None:
    """Arguments of `ros2 param describe`."""
    options.node_and_hidden(parser)
    parser.add_argument("parameter_names", nargs="+", help="Names of the parameters")
    options.timeout(parser)


@verb(
    "param",
    "describe",
    "Show descriptive information about declared parameters",
    arguments=param_describe_arguments,
)
def param_describe(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 param describe <node> <name> [<name> ...]`."""
    node = _find_node(args, ctx)
    if node is None:
        return NODE_NOT_FOUND
    descriptors = ctx.client.describe_parameters(node, args.parameter_names)
    return ctx.console.emit(render.param_describe(descriptors))


def param_dump_arguments(parser: Parser) -> None:
    """Arguments of `ros2 param dump`."""
    options.node_and_hidden(parser)
    options.timeout(parser)


@verb(
    "param",
    "dump",
    "Show all of the parameters of a node in a YAML file format",
    arguments=param_dump_arguments,
)
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


def param_load_arguments(parser: Parser) -> None:
    """Arguments of `ros2 param load`."""
    options.node_and_hidden(parser)
    parser.add_argument("parameter_file", help="Parameter file")
    parser.add_argument(
        "--no-use-wildcard",
        action="store_true",
        help="Do not load parameters in the '/**' namespace into the node",
    )
    options.timeout(parser)


@verb("param", "load", "Load parameter file for a node", arguments=param_load_arguments)
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
    door = f"{current_door()}|params file {os.path.basename(args.parameter_file)}"
    with acting_door(door):  # the history names the file and the door it came through
        results = ctx.client.set_parameters(node, values) if values else []
    return ctx.console.emit(render.param_load(results))
