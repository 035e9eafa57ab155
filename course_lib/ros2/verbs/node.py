"""`ros2 node list|info`: the arguments, the handlers (ask the graph, render, print)."""

from __future__ import annotations

import argparse
from typing import Any

from .. import render
from ..verbkit import options
from ..verbkit.context import Context, settled_client
from ..verbkit.registry import command, verb

__all__ = ["node_info", "node_info_arguments", "node_list", "node_list_arguments"]

Parser = argparse.ArgumentParser


command("node", "Various node related sub-commands")


def node_list_arguments(parser: Parser) -> None:
    """Arguments of `ros2 node list`."""
    options.strategy(parser)
    parser.add_argument(
        "-a", "--all", action="store_true", help="Display all nodes even hidden ones"
    )
    parser.add_argument(
        "-c",
        "--count-nodes",
        action="store_true",
        help="Only display the number of nodes discovered",
    )


def node_info_arguments(parser: Parser) -> None:
    """Arguments of `ros2 node info`."""
    options.strategy(parser)
    parser.add_argument("node_name", help="Node name to request information")
    parser.add_argument(
        "--include-hidden",
        action="store_true",
        help="Display hidden topics, services, and actions as well",
    )


@verb("node", "list", "Output a list of available nodes", arguments=node_list_arguments)
def node_list(args: argparse.Namespace, ctx: Context) -> int:
    """`ros2 node list [-a] [-c]`."""
    names = settled_client(args, ctx).node_names(include_hidden=args.all)
    if not names and not args.count_nodes:
        return 0
    return ctx.console.emit(
        render.node_list([n.full_name for n in names], count_only=args.count_nodes)
    )


@verb("node", "info", "Output information about a node", arguments=node_info_arguments)
def node_info(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 node info <node>`."""
    client = settled_client(args, ctx)

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
