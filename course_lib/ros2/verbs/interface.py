"""`ros2 interface list|package|packages|show|proto` over the installed interface files."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ...core import ament
from ..interface_index import interface_packages, interface_path, interfaces, prefixes
from ..interface_text import show_lines
from ..verbkit.context import Context
from ..verbkit.registry import command, verb

__all__ = [
    "list_",
    "list_arguments",
    "package",
    "package_arguments",
    "packages",
    "packages_arguments",
    "proto",
    "proto_arguments",
    "show",
    "show_arguments",
]

Parser = argparse.ArgumentParser
_ONLY = (
    ("-m", "--only-msgs", "msg", "message"),
    ("-s", "--only-srvs", "srv", "service"),
    ("-a", "--only-actions", "action", "action"),
)
_TYPE_HELP = "Show an interface definition (e.g. 'example_interfaces/msg/String')"


command("interface", "Show information about ROS interfaces")


def _roots(ctx: Context) -> list[Path]:
    return prefixes(dict(ctx.env) if ctx.env else ament.workspace_env())


def _only_flags(parser: Parser) -> None:
    for short, long, _kind, word in _ONLY:
        parser.add_argument(
            short, long, action="store_true", help=f"Print out only the {word} types"
        )


def list_arguments(parser: Parser) -> None:
    """Arguments of `ros2 interface list`."""
    _only_flags(parser)


def package_arguments(parser: Parser) -> None:
    """Arguments of `ros2 interface package`."""
    _only_flags(parser)
    parser.add_argument("package_name", help="Name of the ROS package (e.g. 'example_interfaces')")


def packages_arguments(parser: Parser) -> None:
    """Arguments of `ros2 interface packages`."""
    for short, long, _kind, word in _ONLY:
        parser.add_argument(
            short, long, action="count", help=f"Only list packages that generate {word}s"
        )


class _ReadStdinPipe(argparse.Action):
    """`-` reads the type name from a pipe, as ros2interface's show does."""

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: Any,
        option_string: str | None = None,
    ) -> None:
        if values == "-":
            if sys.stdin.isatty():
                parser.error("expected stdin pipe")
            values = sys.stdin.readline().strip()
        if not values:
            parser.error("the passed value is empty")
        setattr(namespace, self.dest, values)


def show_arguments(parser: Parser) -> None:
    """Arguments of `ros2 interface show`."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--all-comments",
        default=False,
        action="store_true",
        help="Show all comments, including for nested interface definitions",
    )
    group.add_argument(
        "--no-comments",
        default=False,
        action="store_true",
        help="Show no comments or whitespace",
    )
    parser.add_argument(
        "type",
        action=_ReadStdinPipe,
        help=f"{_TYPE_HELP}. Passing '-' reads the argument from stdin (e.g. "
        "'ros2 topic type /chatter | ros2 interface show -').",
    )


def proto_arguments(parser: Parser) -> None:
    """Arguments of `ros2 interface proto`."""
    parser.add_argument("type", help=_TYPE_HELP)
    parser.add_argument(
        "--no-quotes", action="store_true", help="if true output has no outer quotes."
    )


@verb(
    "interface",
    "list",
    "List all interface types available",
    arguments=list_arguments,
    graph=False,
)
def list_(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 interface list [-m] [-s] [-a]`."""
    roots = _roots(ctx)
    titles = {"msg": "Messages:", "srv": "Services:", "action": "Actions:"}
    chosen = [kind for _s, long, kind, _w in _ONLY if getattr(args, long[2:].replace("-", "_"))]
    lines: list[str] = []
    for kind in chosen or list(titles):
        lines.append(titles[kind])
        for pkg, names in sorted(interfaces(roots, kind=kind).items()):
            lines.extend(f"    {pkg}/{name}" for name in names)
    ctx.console.out("".join(f"{line}\n" for line in lines))
    return 0


@verb(
    "interface",
    "package",
    "Output a list of available interface types within one package",
    arguments=package_arguments,
    graph=False,
)
def package(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 interface package <package> [-m] [-s] [-a]` (sorted; the real order is random)."""
    roots = _roots(ctx)
    chosen = [kind for _s, long, kind, _w in _ONLY if getattr(args, long[2:].replace("-", "_"))]
    names: list[str] = []
    try:
        for kind in chosen or [""]:
            names += interfaces(roots, [args.package_name], kind).get(args.package_name, [])
    except LookupError as exc:
        return str(exc)
    ctx.console.out("".join(f"{args.package_name}/{name}\n" for name in names))
    return 0


@verb(
    "interface",
    "packages",
    "Output a list of packages that provide interfaces",
    arguments=packages_arguments,
    graph=False,
)
def packages(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 interface packages [-m|-s|-a]`."""
    roots = _roots(ctx)
    kind = next((k for _s, long, k, _w in _ONLY if getattr(args, long[2:].replace("-", "_"))), "")
    found = sorted(interfaces(roots, kind=kind)) if kind else interface_packages(roots)
    ctx.console.out("".join(f"{name}\n" for name in found))
    return 0


@verb(
    "interface", "show", "Output the interface definition", arguments=show_arguments, graph=False
)
def show(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 interface show <type> [--all-comments|--no-comments]`."""
    roots = _roots(ctx)
    try:
        lines = list(
            show_lines(
                args.type,
                lambda name: interface_path(name, roots).read_text(),
                comments=not args.no_comments,
                nested_comments=args.all_comments,
            )
        )
    except (ValueError, LookupError) as exc:
        return str(exc)
    ctx.console.out("".join(f"{line}\n" for line in lines))
    return 0


@verb(
    "interface", "proto", "Output an interface prototype", arguments=proto_arguments, graph=False
)
def proto(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 interface proto <type> [--no-quotes]`: a default instance as YAML."""
    from ..msgfill import import_type
    from ..msgyaml import message_to_yaml

    parts = args.type.split("/")
    interface = import_type(args.type, parts[1] if len(parts) == 3 else "msg")
    if hasattr(interface, "Goal"):
        instance = interface.Goal()
    elif hasattr(interface, "Request"):
        instance = interface.Request()
    else:
        instance = interface()
    text = message_to_yaml(instance, truncate_length=None)
    ctx.console.out(f"{text}\n" if args.no_quotes else f'"{text}"\n')
    return 0
