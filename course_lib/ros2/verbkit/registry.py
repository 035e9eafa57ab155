"""The one way to register a `ros2` command or verb: a declaration beside its code (pure).

A verb module says what it offers where it defines it, as ros2cli's packages do through
their entry points::

    command("param", "Various param related sub-commands")

    def param_set_arguments(parser): ...

    @verb("param", "set", "Set parameter", arguments=param_set_arguments)
    def param_set(args, ctx): ...

`course_lib/ros2/command/verb_index.py` is generated from these declarations (so a terminal's
`ros2` reads one small table instead of importing every verb); a unit test fails, naming the
command that rewrites it, when the two differ.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

__all__ = [
    "CommandDeclaration",
    "DeclarationError",
    "VerbDeclaration",
    "command",
    "command_verb",
    "declared_commands",
    "declared_verbs",
    "raw_command",
    "verb",
]

Handler = TypeVar("Handler", bound=Callable[..., Any])
Builder = Callable[[Any], None]
_PACKAGE = "course_lib.ros2."
OWN = ""  # the verb name of a command that is itself a verb (`ros2 run`)


class DeclarationError(ValueError):
    """A command or verb declared twice, or a handler outside course_lib.ros2."""


@dataclass(frozen=True)
class CommandDeclaration:
    """`ros2 <name>`: its help line, the options it takes before its verb, or its raw handler."""

    name: str
    doc: str
    options: str | None = None  # `module:function` (module relative to course_lib.ros2)
    raw: str | None = None  # handler(argv after the command, ctx) that parses argv itself


@dataclass(frozen=True)
class VerbDeclaration:
    """`ros2 <command> <name>` (name OWN: the command itself): help line, handler, builder."""

    command: str
    name: str
    doc: str
    handler: str
    arguments: str | None = None
    graph: bool = True  # False: never needs the ROS graph (terminals run it without the daemon)


_commands: dict[str, CommandDeclaration] = {}
_verbs: dict[tuple[str, str], VerbDeclaration] = {}


def _name_of(function: Callable[..., Any] | None) -> str | None:
    """Return `module:function` of a function of course_lib.ros2 (None for None)."""
    if function is None:
        return None
    module = function.__module__
    if not module.startswith(_PACKAGE):
        raise DeclarationError(f"{function.__qualname__} is not in course_lib.ros2 ({module})")
    return f"{module.removeprefix(_PACKAGE)}:{function.__qualname__}"


def _keep(table: dict[Any, Any], key: Any, declaration: Any, what: str) -> None:
    """Record a declaration once; the same one again (a re-imported module) changes nothing."""
    known = table.get(key)
    if known is not None and known != declaration:
        raise DeclarationError(f"{what} is declared twice: {known} and {declaration}")
    table[key] = declaration


def command(name: str, doc: str, *, options: Builder | None = None) -> None:
    """Declare `ros2 <name>`, a command of verbs, with the options it takes before its verb."""
    declaration = CommandDeclaration(name, doc, _name_of(options))
    _keep(_commands, name, declaration, f"`ros2 {name}`")


def verb(
    command: str, name: str, doc: str, *, arguments: Builder | None = None, graph: bool = True
) -> Callable[[Handler], Handler]:
    """Register the decorated `handler(args, ctx)` as `ros2 <command> <name>`.

    Args:
        command: the command word (`param`); declare it once with `command(...)`.
        name: the verb word (`set`).
        doc: the help line `ros2 <command> -h` lists.
        arguments: `builder(parser)` adding the verb's arguments.
        graph: False when the verb never needs the ROS graph (run in the terminal itself).
    """

    def register(handler: Handler) -> Handler:
        handler_name = _name_of(handler)
        assert handler_name is not None
        declaration = VerbDeclaration(command, name, doc, handler_name, _name_of(arguments), graph)
        _keep(_verbs, (command, name), declaration, f"`ros2 {command} {name}`".rstrip())
        return handler

    return register


def command_verb(
    name: str, doc: str, *, arguments: Builder | None = None, graph: bool = True
) -> Callable[[Handler], Handler]:
    """Register the decorated handler as `ros2 <name>`, a command without sub-verbs."""

    def register(handler: Handler) -> Handler:
        _keep(_commands, name, CommandDeclaration(name, doc), f"`ros2 {name}`")
        return verb(name, OWN, doc, arguments=arguments, graph=graph)(handler)

    return register


def raw_command(name: str, doc: str) -> Callable[[Handler], Handler]:
    """Register the decorated `handler(argv, ctx)` as `ros2 <name>`, which parses argv itself."""

    def register(handler: Handler) -> Handler:
        declaration = CommandDeclaration(name, doc, raw=_name_of(handler))
        _keep(_commands, name, declaration, f"`ros2 {name}`")
        return handler

    return register


def declared_commands() -> dict[str, CommandDeclaration]:
    """Return the commands declared by the verb modules imported so far, by name."""
    return dict(_commands)


def declared_verbs() -> dict[tuple[str, str], VerbDeclaration]:
    """Return the verbs declared so far, by (command, verb); verb OWN for a command's own."""
    return dict(_verbs)
