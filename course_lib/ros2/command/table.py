"""The one table of `ros2` commands and verbs: docs, handler, argument builder, door (pure).

Adding a verb means one module in course_lib/ros2/verbs (with `add_arguments(parser)` and
`main(args, ctx)`) and one line here. Handlers and builders are named, not imported, so this
table imports nothing and a terminal command loads only the modules of the verb it runs.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any, NamedTuple

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


class Verb:
    """One runnable verb: its help line, `module[:function]` of its handler and its builder.

    `handler="verbs.service_call"` means `verbs.service_call.main` and its `add_arguments`;
    `graph=False` verbs never need the ROS graph, so terminals run them without the daemon.
    """

    __slots__ = ("arguments", "doc", "graph", "handler")

    def __init__(
        self, doc: str, handler: str, arguments: str | None = None, *, graph: bool = True
    ) -> None:
        self.doc = doc
        self.handler = handler if ":" in handler else f"{handler}:main"
        self.arguments = arguments or (None if ":" in handler else f"{handler}:add_arguments")
        self.graph = graph


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


def _interface(name: str, doc: str) -> Verb:
    arguments = f"verbs.interface:{name.rstrip('_')}_arguments"
    return Verb(doc, f"verbs.interface:{name}", arguments, graph=False)


_T = "verbs.topic:"
COMMANDS: dict[str, Command] = {
    "daemon": Command(
        "Various daemon related sub-commands",
        {
            "start": Verb(
                "Start the daemon if it isn't running",
                "verbs.daemon:daemon_start",
                "verbs.daemon:daemon_start_arguments",
                graph=False,
            ),
            "status": Verb(
                "Output the status of the daemon", "verbs.daemon:daemon_status", graph=False
            ),
            "stop": Verb(
                "Stop the daemon if it is running", "verbs.daemon:daemon_stop", graph=False
            ),
        },
    ),
    "interface": Command(
        "Show information about ROS interfaces",
        {
            "list": _interface("list_", "List all interface types available"),
            "package": _interface(
                "package", "Output a list of available interface types within one package"
            ),
            "packages": _interface(
                "packages", "Output a list of packages that provide interfaces"
            ),
            "proto": _interface("proto", "Output an interface prototype"),
            "show": _interface("show", "Output the interface definition"),
        },
    ),
    "launch": Command("Run a launch file", raw="verbs.launch:main"),
    "node": Command(
        "Various node related sub-commands",
        {
            "info": Verb(
                "Output information about a node",
                "verbs.node:node_info",
                "verbs.node:node_info_arguments",
            ),
            "list": Verb(
                "Output a list of available nodes",
                "verbs.node:node_list",
                "verbs.node:node_list_arguments",
            ),
        },
    ),
    "param": Command(
        "Various param related sub-commands",
        {
            "delete": Verb(
                "Delete parameter",
                "verbs.param:param_delete",
                "verbs.param:param_delete_arguments",
            ),
            "describe": Verb(
                "Show descriptive information about declared parameters",
                "verbs.param:param_describe",
                "verbs.param:param_describe_arguments",
            ),
            "dump": Verb(
                "Show all of the parameters of a node in a YAML file format",
                "verbs.param:param_dump",
                "verbs.param:param_dump_arguments",
            ),
            "get": Verb(
                "Get parameter", "verbs.param:param_get", "verbs.param:param_get_arguments"
            ),
            "list": Verb(
                "Output a list of available parameters",
                "verbs.param:param_list",
                "verbs.param:param_list_arguments",
            ),
            "load": Verb(
                "Load parameter file for a node",
                "verbs.param:param_load",
                "verbs.param:param_load_arguments",
            ),
            "set": Verb(
                "Set parameter", "verbs.param:param_set", "verbs.param:param_set_arguments"
            ),
        },
    ),
    "pkg": Command(
        "Various package related sub-commands",
        {
            "create": Verb("Create a new ROS 2 package", "verbs.pkg.create", graph=False),
            "executables": Verb(
                "Output a list of package specific executables",
                "verbs.pkg.executables:pkg_executables",
                "verbs.pkg.executables:pkg_executables_arguments",
                graph=False,
            ),
            "prefix": Verb(
                "Output the prefix path of a package",
                "verbs.pkg.executables:pkg_prefix",
                "verbs.pkg.executables:pkg_prefix_arguments",
                graph=False,
            ),
        },
    ),
    "run": Command(
        "Run a package specific executable",
        own=Verb(
            "Run a package specific executable",
            "verbs.pkg.executables:run",
            "verbs.pkg.executables:run_arguments",
            graph=False,
        ),
    ),
    "service": Command(
        "Various service related sub-commands",
        {
            "call": Verb("Call a service", "verbs.service_call"),
            "find": Verb(
                "Output a list of available services of a given type",
                "verbs.service:find",
                "verbs.service:find_arguments",
            ),
            "info": Verb(
                "Print information about a service",
                "verbs.service:info",
                "verbs.service:info_arguments",
            ),
            "list": Verb(
                "Output a list of available services",
                "verbs.service:list_",
                "verbs.service:list_arguments",
            ),
            "type": Verb(
                "Output a service's type", "verbs.service:type_", "verbs.service:type_arguments"
            ),
        },
        leading="verbs.service:command_arguments",
    ),
    "topic": Command(
        "Various topic related sub-commands",
        {
            "bw": Verb("Display bandwidth used by topic", "verbs.topic:bw", _T + "bw_arguments"),
            "delay": Verb(
                "Display delay of topic from timestamp in header",
                "verbs.topic:delay",
                _T + "delay_arguments",
            ),
            "echo": Verb(
                "Output messages from a topic",
                "verbs.topic_stream:topic_echo",
                "verbs.topic_stream:topic_echo_arguments",
            ),
            "find": Verb(
                "Output a list of available topics of a given type",
                "verbs.topic:find",
                _T + "find_arguments",
            ),
            "hz": Verb(
                "Print the average publishing rate to screen",
                "verbs.topic_stream:topic_hz",
                "verbs.topic_stream:topic_hz_arguments",
            ),
            "info": Verb(
                "Print information about a topic", "verbs.topic:info", _T + "info_arguments"
            ),
            "list": Verb(
                "Output a list of available topics",
                "verbs.topic:topic_list",
                "verbs.topic:topic_list_arguments",
            ),
            "pub": Verb("Publish a message to a topic", "verbs.topic_pub"),
            "type": Verb("Print a topic's type", "verbs.topic:type_", _T + "type_arguments"),
        },
        leading="verbs.topic:topic_command_arguments",
    ),
}

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
