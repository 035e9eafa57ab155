"""`ros2 service list|type|find|info` (ros2service 0.32.2's arguments and output)."""

from __future__ import annotations

import argparse
from typing import Any

from ..node.graph import services, types_of
from ..verbkit import options
from ..verbkit.context import Context
from ..verbkit.registry import command, verb

__all__ = [
    "command_arguments",
    "find",
    "find_arguments",
    "info",
    "info_arguments",
    "list_",
    "list_arguments",
    "type_",
    "type_arguments",
]

Parser = argparse.ArgumentParser
_HIDDEN_HELP = "Consider hidden services as well"
_COUNT_HELP = "Only display the number of services discovered"


def command_arguments(parser: Parser) -> None:
    """The option `ros2 service` itself takes before its verb."""
    parser.add_argument("--include-hidden-services", action="store_true", help=_HIDDEN_HELP)


command("service", "Various service related sub-commands", options=command_arguments)


def list_arguments(parser: Parser) -> None:
    """Arguments of `ros2 service list`."""
    options.strategy(parser)
    parser.add_argument(
        "-t", "--show-types", action="store_true", help="Additionally show the service type"
    )
    parser.add_argument("-c", "--count-services", action="store_true", help=_COUNT_HELP)
    parser.add_argument("--include-hidden-services", action="store_true", help=_HIDDEN_HELP)


def type_arguments(parser: Parser) -> None:
    """Arguments of `ros2 service type`."""
    parser.add_argument(
        "service_name",
        help="Name of the ROS service to get type (e.g. '/talker/list_parameters')",
    )


def find_arguments(parser: Parser) -> None:
    """Arguments of `ros2 service find`."""
    parser.add_argument(
        "service_type",
        help="Name of the ROS service type to filter for "
        "(e.g. 'rcl_interfaces/srv/ListParameters')",
    )
    parser.add_argument("-c", "--count-services", action="store_true", help=_COUNT_HELP)
    parser.add_argument("--include-hidden-services", action="store_true", help=_HIDDEN_HELP)


def info_arguments(parser: Parser) -> None:
    """Arguments of `ros2 service info`."""
    options.strategy(parser)
    parser.add_argument(
        "service_name", help="Name of the ROS service to get info (e.g. '/add_two_ints')"
    )


def _services(args: argparse.Namespace, ctx: Context) -> list[tuple[str, list[str]]]:
    ctx.client.settle()
    return services(ctx.client, include_hidden=args.include_hidden_services)


def _types_of(args: argparse.Namespace, ctx: Context) -> list[str] | None:
    return types_of(
        ctx.client, args.service_name, kind="service",
        include_hidden=args.include_hidden_services,
    )  # fmt: skip


@verb("service", "list", "Output a list of available services", arguments=list_arguments)
def list_(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 service list [-t] [-c] [--include-hidden-services]`."""
    found = _services(args, ctx)
    if args.count_services:
        ctx.console.out(f"{len(found)}\n")
        return 0
    suffix = (lambda types: f" [{', '.join(types)}]") if args.show_types else (lambda _t: "")
    ctx.console.out("".join(f"{name}{suffix(types)}\n" for name, types in found))
    return 0


@verb("service", "type", "Output a service's type", arguments=type_arguments)
def type_(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 service type <service>`: its type, or exit 1 silently."""
    types = _types_of(args, ctx)
    if types is None:
        return 1
    ctx.console.out("".join(f"{t}\n" for t in types))
    return 0


@verb(
    "service",
    "find",
    "Output a list of available services of a given type",
    arguments=find_arguments,
)
def find(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 service find <type> [-c]`."""
    names = [name for name, types in _services(args, ctx) if args.service_type in types]
    text = f"{len(names)}\n" if args.count_services else "".join(f"{n}\n" for n in names)
    ctx.console.out(text)
    return 0


@verb("service", "info", "Print information about a service", arguments=info_arguments)
def info(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 service info <service>`: type, clients and servers."""
    types = _types_of(args, ctx)
    if types is None:
        return f"Unknown service '{args.service_name}'"
    node = ctx.client.node
    shown = types[0] if len(types) == 1 else types
    # The course's client node keeps parameter clients open: they are not the learner's.
    mine = sum(
        name == args.service_name
        for name, _types in node.get_client_names_and_types_by_node(
            node.get_name(), node.get_namespace()
        )
    )
    ctx.console.out(
        f"Type: {shown}\n"
        f"Clients count: {node.count_clients(args.service_name) - mine}\n"
        f"Services count: {node.count_services(args.service_name)}\n"
    )
    return 0
