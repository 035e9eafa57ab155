"""One course hint under a `ros2` command's exact Jazzy text, for the mistakes learners make most.

Only notebooks show these hints (the `%ros2` magic, a lesson's run and launch); the terminal's
`ros2` never does, and a hint never changes the text Jazzy prints: it comes after it, apart.
The pure functions (closest name, a value split at its spaces or followed by a unit, a type
mismatch, a velocity the robot cannot reach, a `ros2 run` of a name that does not exist, a
params file's sections) take what the command printed and what the graph shows; `command_hint`
and `params_file_hints` read the live graph, the nodes' parameter lists, the ament index and
the lab's journal (a node another lesson stopped) for them.
"""

from __future__ import annotations

import html
import os
import re
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

from ..core.errors import CourseError
from ..ros2.paramfile import key_matches, params_files
from .file_hints import file_sections, section_hints, started_nodes
from .run_hints import NO_EXECUTABLE, NO_PACKAGE, file_crash_hint, run_hint, run_words
from .start_command import last_start_command
from .value_hints import (
    absolute,
    closest,
    joined_value,
    missing_name_hint,
    positionals,
    split_hint,
    top_speed_hint,
    type_hint,
    unit_hint,
)

__all__ = [
    "PREFIX",
    "as_html",
    "as_text",
    "closest",
    "command_hint",
    "crash_hint",
    "enabled",
    "file_sections",
    "joined_value",
    "key_matches",
    "params_file_hints",
    "params_files",
    "run_hint",
    "run_words",
    "section_hints",
    "set_enabled",
    "split_hint",
    "started_nodes",
    "top_speed_hint",
    "type_hint",
    "unit_hint",
]

PREFIX = "Hint: "
NODE_NOT_FOUND = "Node not found"
PARAMETER_NOT_SET = "Parameter not set"
UNDECLARED = "Setting parameter failed: Invalid access to undeclared parameter(s)"
UNABLE_TO_FIND = re.compile(r"Unable to find node '([^']*)'")

STYLE = (
    "font-family:sans-serif;white-space:pre-wrap;margin:4px 0 0 0;padding:2px 8px;"
    "border-left:3px solid #1565c0;background:#e3f2fd;color:#0d47a1"
)

_enabled = True


def set_enabled(on: bool) -> None:
    """Turn the hints on or off for this kernel (a lesson does it from `show_hints`)."""
    global _enabled
    _enabled = bool(on)


def enabled() -> bool:
    """Return whether this kernel shows hints."""
    return _enabled


def as_text(hints: Sequence[str]) -> str:
    """Return hints as plain-text lines (`Hint: ...`), for nbval and a terminal-like view."""
    return "".join(f"{PREFIX}{hint}\n" for hint in hints)


def as_html(hints: Sequence[str]) -> str:
    """Return hints as HTML lines set apart (blue, left rule) from a command's output."""
    return "".join(
        f'<div class="course-hint" style="{STYLE}">{html.escape(PREFIX + hint)}</div>'
        for hint in hints
    )


def crash_hint(log_lines: Iterable[str], files: Sequence[str], *, cwd: str = "") -> str | None:
    """Return the hint for a node that a params file stopped at start-up, or None (hints off,
    or no params file): see `run_hints.file_crash_hint`."""
    return file_crash_hint(log_lines, files, cwd=cwd) if _enabled else None


# --- live: the graph and the nodes' parameters ----------------------------------------------
def _node_names(client: Any) -> list[str]:
    """Return the full names of the nodes the graph shows (no waiting)."""
    return sorted(n.full_name for n in client.node_names())


def _parameter_names(client: Any, node: str) -> list[str]:
    """Return the node's parameter names, or [] if it does not answer."""
    from ..ros2.node.client import ServiceCallError  # rclpy: only once a command failed

    try:
        return sorted(client.list_parameters(node))
    except (ServiceCallError, CourseError):  # a hint never turns a command into a failure
        return []


def _param_hint(words: list[str], stdout: str, stderr: str, client: Any) -> str | None:
    """Return the hint for a failed `param get|set|describe NODE NAME [VALUE]`, or None.

    `param describe` of an undeclared name prints nothing at all in Jazzy: that is a mistake
    too, found by asking the node for its parameter names.
    """
    if len(words) < 3 or words[1] not in ("get", "set", "describe", "delete", "dump", "list"):
        return None
    node = absolute(words[2])
    if stderr.startswith(NODE_NOT_FOUND):
        return _missing_node_hint(node, _node_names(client))
    if len(words) < 4:
        return None
    name, show = words[3], f"`%ros2 param list {node}`"
    if stderr.startswith(UNDECLARED) or stderr.startswith(PARAMETER_NOT_SET):
        return missing_name_hint("parameter", name, _parameter_names(client, node), show)
    if words[1] == "describe" and not stdout and not stderr:
        known = _parameter_names(client, node)
        missing = [n for n in words[3:] if known and n not in known]
        return missing_name_hint("parameter", missing[0], known, show) if missing else None
    if words[1] == "set" and len(words) >= 5:
        return type_hint(stderr, name, words[4])
    return None


def _missing_node_hint(node: str, running: Sequence[str]) -> str:
    """Say why `node` is not found: another lesson stopped it, a running node has a close
    name, or it ran in this lab before (with the command that started it), else that no node
    has that name."""
    stopped = _stopped_hint(node, running)
    if stopped is not None:
        return stopped
    domain = os.environ.get("ROS_DOMAIN_ID")
    again = last_start_command(node, domain) if domain and closest(node, running) is None else None
    if again:
        return f"{node} is not running now (it ran in this lab before): start it again: `{again}`."
    return missing_name_hint("node", node, running, "`%ros2 node list`")


def _stopped_hint(node: str, running: Sequence[str]) -> str | None:
    """Return the hint for a node that another lesson stopped (the lab's journal says so, and
    the node whose start stopped it is among the `running` ones), with the command that
    starts it again; None when the records cannot tell."""
    from ..core import ament
    from ..lab.takeover import stopped_by_a_lesson

    stopped = stopped_by_a_lesson(node, os.environ.get("ROS_DOMAIN_ID"))
    if stopped is None or stopped.started not in running:  # a journal of an older lab
        return None
    package = ament.package_of_executable(stopped.executable, ament.workspace_env())
    again = (
        f"start it again with `%ros2 run {package} {stopped.executable}`"
        if package
        else f"start it again as {stopped.started_by} did"
    )
    return (
        f"{node} is not running: {stopped.by} stopped it when it started {stopped.started} "
        f"(one node at a time drives your lab's robot). To use it here, {again} (that stops "
        f"{stopped.started} in turn)."
    )


def _live_run_hint(argv: Sequence[str], stderr: str) -> str | None:
    """Return the hint for a `ros2 run` whose package or executable does not exist."""
    from ..core import ament
    from ..core.errors import PackageNotFoundError

    words = run_words(argv)
    said = stderr.strip()  # a node that started prints its log lines there too
    if words is None or not (said == NO_EXECUTABLE or NO_PACKAGE.fullmatch(said)):
        return None
    env = ament.workspace_env()

    def executables_of(package: str) -> list[str]:
        try:
            return ament.package_executables(package, env)
        except PackageNotFoundError:
            return []

    return run_hint(stderr, words, sorted(ament.list_packages(env)), executables_of)


def command_hint(
    argv: Sequence[str], stdout: str, stderr: str, client: Callable[[], Any]
) -> str | None:
    """Return one hint for the mistake a `ros2` command line shows in its output, or None.

    Runs after a failure Jazzy reports, a `param describe` that printed nothing, or a
    velocity the robot cannot reach set on the tutorial's node (nothing is asked of the graph
    otherwise).
    """
    words = positionals(argv)
    if not _enabled:
        return None
    if not stderr:
        if words[:2] == ["param", "describe"] and not stdout:
            return _param_hint(words, stdout, stderr, client())
        return top_speed_hint(words, stdout)
    value = joined_value(argv)
    if value is not None and "unrecognized arguments" in stderr:
        return unit_hint(words) or split_hint(value)
    if words[:1] == ["param"] and len(words) > 1:
        return _param_hint(words, stdout, stderr, client())
    if words[:1] == ["run"]:
        return _live_run_hint(argv, stderr)
    missing = UNABLE_TO_FIND.search(stderr)
    if words[:2] == ["node", "info"] and missing:
        return _missing_node_hint(absolute(missing.group(1)), _node_names(client()))
    return None


def params_file_hints(
    files: Sequence[str], nodes: Sequence[str], client: Callable[[], Any], cwd: str | None = None
) -> list[str]:
    """Return the hints for params files given to the nodes `nodes` just started (read from
    disk; each node's declared parameters asked of the running node)."""
    if not _enabled or not files or not nodes:
        return []
    live = client()
    declared = {node: _parameter_names(live, node) for node in nodes}
    declared = {node: names for node, names in declared.items() if names}
    hints: list[str] = []
    for file in files:
        path = Path(cwd or ".") / file
        try:
            text = path.read_text(encoding="utf-8")
        except OSError:
            continue  # ROS itself says so (the node does not start)
        hints += section_hints(file, file_sections(text, name=file), declared)
    return hints
