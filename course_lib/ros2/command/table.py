"""The one table of `ros2` commands and verbs: docs, handler, argument builder, door (pure).

A verb is registered once, beside its code (`@verb("param", "set", ...)` on its handler in
course_lib/ros2/verbs; see course_lib/ros2/verbkit/registry.py). This table reads
`verb_index.py`, generated from those declarations, so it imports no verb module: handlers and
builders are named `module:function` and imported on first use, and a terminal command loads
only the modules of the verb it runs.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any, NamedTuple

from . import verb_index

__all__ = [
    "COMMANDS",
    "ELSEWHERE",
    "Command",
    "Verb",
    "absent_hint",
    "available",
    "resolve",
    "verb_of",
]


class Verb(NamedTuple):
    """One runnable verb: its help line, `module:function` of its handler and of its builder.

    `graph=False` verbs never need the ROS graph, so terminals run them without the daemon.
    """

    doc: str
    handler: str
    arguments: str | None = None
    graph: bool = True


class Command(NamedTuple):
    """A `ros2 <command>`: its help line, then either sub-verbs or a verb of its own."""

    doc: str
    verbs: dict[str, Verb] | None = None
    own: Verb | None = None
    leading: str | None = None  # builder of options taken before the verb
    raw: str | None = None  # handler(argv after the command, ctx) that parses argv itself


def resolve(name: str) -> Callable[..., Any]:
    """Return the function `module:function` of course_lib.ros2 (imported on first use)."""
    module, _, function = name.partition(":")
    return getattr(importlib.import_module(f"course_lib.ros2.{module}"), function)


def _commands() -> dict[str, Command]:
    """Build the table from verb_index (written from the declarations beside each verb)."""
    verbs: dict[str, dict[str, Verb]] = {}
    for (command, name), (doc, handler, arguments, graph) in verb_index.VERBS.items():
        verbs.setdefault(command, {})[name] = Verb(doc, handler, arguments, graph=graph)
    table: dict[str, Command] = {}
    for name, (doc, options, raw) in verb_index.COMMANDS.items():
        own = verbs.get(name, {}).pop("", None)  # verb "": the command is the verb
        table[name] = Command(
            doc, verbs.get(name) if own is None and raw is None else None, own, options, raw
        )
    return table


COMMANDS: dict[str, Command] = _commands()

# What the real `ros2` has and the course does not: the hint says what to use instead.
ELSEWHERE: dict[str, str] = {
    "action": "The course's nodes offer no actions; parameters are services: "
    "try `ros2 service list`.",
    "bag": "The course records nothing; watch messages live with `ros2 topic echo <topic>`.",
    "component": "The course starts nodes as processes: use `ros2 run` or `ros2 launch`.",
    "doctor": "Check the course's setup with `make doctor` (or `python -m course_lib doctor`).",
    "extension_points": "The course's ros2 has no extensions; `ros2 --help` lists its commands.",
    "extensions": "The course's ros2 has no extensions; `ros2 --help` lists its commands.",
    "lifecycle": "The course's nodes are plain (not managed) nodes: see `ros2 node list`.",
    "multicast": "The course runs on one machine with localhost discovery: nothing to test.",
    "security": "The course runs without SROS2 security.",
    "wtf": "Check the course's setup with `make doctor` (or `python -m course_lib doctor`).",
    "pkg list": "Try `ros2 pkg executables` to see the course's packages and programs.",
    "pkg xml": "Read the manifest directly: `cat $(ros2 pkg prefix --share <package>)"
    "/package.xml`.",
    "service echo": "Watch a service's effect instead, e.g. `ros2 topic echo /parameter_events`.",
}


def available() -> list[str]:
    """Return the commands the course has, sorted."""
    return sorted(COMMANDS)


def absent_hint(words: str) -> str | None:
    """Return the hint for a real `ros2` command or verb the course lacks, else None."""
    command, _, verb = words.partition(" ")
    known = COMMANDS.get(command)
    if known is not None and (not verb or (known.verbs and verb in known.verbs)):
        return None
    return ELSEWHERE.get(words)


def verb_of(argv: list[str]) -> tuple[str | None, str | None]:
    """Return (command, verb) named in argv (None where absent), without parsing options."""
    words = [w for w in argv if not w.startswith("-")]
    if not words:
        return None, None
    command = COMMANDS.get(words[0])
    if command is None or command.verbs is None or len(words) < 2:
        return words[0], None
    return words[0], words[1]


def uses_graph(argv: list[str]) -> bool:
    """Return whether this command line needs the ROS graph (terminals: via the daemon)."""
    name, verb = verb_of(argv)
    command = COMMANDS.get(name or "")
    if command is None or command.raw is not None:
        return False
    if command.own is not None:
        return command.own.graph
    chosen = (command.verbs or {}).get(verb or "")
    return chosen is not None and chosen.graph
