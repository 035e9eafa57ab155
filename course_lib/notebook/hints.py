"""One course hint under a `ros2` command's exact Jazzy text, for the mistakes learners make most.

Only notebooks show these hints (the `%ros2` magic, a lesson's run and launch); the terminal's
`ros2` never does, and a hint never changes the text Jazzy prints: it comes after it, apart.
The pure functions (closest name, a value split at its spaces, a type mismatch, a params file's
sections) take what the command printed and what the graph shows; `command_hint` and
`params_file_hints` read the live graph and the nodes' parameter lists for them.
"""

from __future__ import annotations

import difflib
import html
import itertools
import os
import re
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

import yaml

from ..core.bounded_yaml import safe_load_bounded
from ..core.errors import CourseError
from ..lab.register import node_name_from_log

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
    "set_enabled",
    "started_nodes",
    "type_hint",
]

PREFIX = "Hint: "
NODE_NOT_FOUND = "Node not found"
PARAMETER_NOT_SET = "Parameter not set"
UNDECLARED = "Setting parameter failed: Invalid access to undeclared parameter(s)"
WRONG_TYPE = re.compile(r"Wrong parameter type, expected 'Type\.(\w+)' got 'Type\.(\w+)'")
UNABLE_TO_FIND = re.compile(r"Unable to find node '([^']*)'")
FILE_TYPE_CRASH = re.compile(  # rclpy's words when a params file's value has the wrong type
    r"InvalidParameterTypeException: Trying to set parameter '([^']+)' to '([^']*)' of type "
    r"'(\w+)', expecting type '(\w+)'"
)
FILE_UNREAD_CRASH = re.compile(  # rcl's words when it cannot open or parse a params file
    r"Couldn't parse params file: '--params-file (?P<file>[^']+)'\. Error: (?P<error>.+?)"
    r"(?:, at [^,]+:\d+)*$"
)
_VALUED_OPTIONS = {"--timeout", "--spin-time", "--filter", "--param-prefixes"}
_WORDS = {
    "DOUBLE": "a double (a number with a decimal point)",
    "INTEGER": "an integer",
    "BOOL": "a bool",
    "STRING": "a string",
    "BYTE_ARRAY": "a byte array",
    "BOOL_ARRAY": "an array of bools",
    "INTEGER_ARRAY": "an array of integers",
    "DOUBLE_ARRAY": "an array of doubles",
    "STRING_ARRAY": "an array of strings",
}
_EXAMPLES = {
    "DOUBLE": "0.2",
    "INTEGER": "3",
    "BOOL": "true",
    "STRING": "hello",
    "BOOL_ARRAY": "'[true, false]'",
    "INTEGER_ARRAY": "'[1, 2]'",
    "DOUBLE_ARRAY": "'[1.0, 2.0]'",
    "STRING_ARRAY": "'[a, b]'",
}

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


# --- pure: names ----------------------------------------------------------------------------
def closest(name: str, known: Iterable[str]) -> str | None:
    """Return the known name most like `name` (difflib, ratio >= 0.6), or None."""
    candidates = sorted(set(known) - {name})
    match = difflib.get_close_matches(name, candidates, n=1, cutoff=0.6)
    return match[0] if match else None


def _missing_name_hint(what: str, name: str, known: Sequence[str], show: str) -> str:
    """Say that `name` does not exist and which existing one it is most like."""
    near = closest(name, known)
    if near is not None:
        return f"there is no {what} '{name}'; did you mean '{near}'? ({show} lists them)"
    if not known and what == "node":
        return f"no node is running, so there is no '{name}': start the node first."
    return f"there is no {what} '{name}' and none with a close name; {show} lists them."


# --- pure: the command line -----------------------------------------------------------------
def _positionals(argv: Sequence[str]) -> list[str]:
    """Return the arguments of a `ros2` command line that are not options or their values."""
    found: list[str] = []
    skip = False
    for token in argv:
        if skip:
            skip = False
            continue
        if token in _VALUED_OPTIONS:
            skip = True
            continue
        if token.startswith("-") and not re.match(r"-[\d.]", token):
            continue
        found.append(token)
    return found


def joined_value(argv: Sequence[str]) -> str | None:
    """Return the value of `param set NODE NAME VALUE...` when it was split into several
    arguments at its spaces (by the shell or the magic), joined again; else None."""
    words = _positionals(argv)
    if words[:2] != ["param", "set"] or len(words) <= 5:
        return None
    return " ".join(words[4:])


def _format_double(text: str) -> str:
    """Return the double a learner meant by `text` (`1` -> `1.0`, `0,5` -> `0.5`)."""
    text = text.strip().strip("'\"").replace(",", ".")
    try:
        return repr(float(text))
    except ValueError:
        return _EXAMPLES["DOUBLE"]


def type_hint(reason: str, name: str, value: str) -> str | None:
    """Return the hint for Jazzy's `Wrong parameter type` reason, or None for another one."""
    match = WRONG_TYPE.search(reason)
    if match is None:
        return None
    expected, got = match.groups()
    kind = _WORDS.get(expected, expected.lower())
    if expected == "DOUBLE" and got in ("INTEGER", "STRING"):
        what = "an integer" if got == "INTEGER" else "text"
        return (
            f"'{name}' is {kind}; `{value}` was read as {what} and ROS does not convert it: "
            f"write `{_format_double(value)}`."
        )
    if expected == "INTEGER" and got == "DOUBLE":
        return f"'{name}' is {kind}; write it without a decimal point, e.g. `{int(float(value))}`."
    if expected.endswith("_ARRAY"):
        return (
            f"'{name}' is {kind}: write it in brackets and in quotes, as one argument, "
            f"e.g. {_EXAMPLES.get(expected, _EXAMPLES['DOUBLE_ARRAY'])}."
        )
    if expected == "STRING":
        return (
            f"'{name}' is {kind}; `{value}` was read as a number or bool: quote it, '\"{value}\"'."
        )
    return f"'{name}' is {kind}; write a value of that type, e.g. `{_EXAMPLES.get(expected, '')}`."


def split_hint(value: str) -> str:
    """Return the hint for a value the shell or the magic split at its spaces."""
    count = len(value.split())
    return (
        f"the value `{value}` was split at its spaces into {count} arguments: "
        f"put it in quotes, as one argument: '{value}'."
    )


# --- pure: params files ---------------------------------------------------------------------
def params_files(argv: Sequence[str]) -> list[str]:
    """Return the files given to `--params-file` after `--ros-args` in a command line."""
    tokens = list(argv)
    if "--ros-args" not in tokens:
        return []
    tokens = tokens[tokens.index("--ros-args") + 1 :]
    return [b for a, b in itertools.pairwise(tokens) if a == "--params-file"]


def key_matches(key: str, node: str) -> bool:
    """Return whether a params file's top-level key selects the node `node` (`/ns/name`):
    the node's full name (a leading slash may be left out), `/**` or a `*` pattern."""
    pattern = re.escape("/" + key.lstrip("/")).replace(r"\*\*", ".*").replace(r"\*", "[^/]*")
    return re.fullmatch(pattern, "/" + node.lstrip("/")) is not None


def _flat_names(tree: Any, prefix: str = "") -> list[str]:
    """Return the dotted parameter names of a `ros__parameters` mapping."""
    if not isinstance(tree, dict):
        return []
    names: list[str] = []
    for key, value in tree.items():
        full = f"{prefix}{key}"
        names += _flat_names(value, full + ".") if isinstance(value, dict) else [full]
    return names


def file_sections(text: str, name: str = "<params>") -> dict[str, list[str]]:
    """Return each top-level key of a params file with the parameter names under it
    (empty on a file that is not a mapping: ROS itself reports those)."""
    try:
        data = safe_load_bounded(text, name=name) if text.strip() else None
    except (yaml.YAMLError, ValueError):
        return {}
    if not isinstance(data, dict):
        return {}
    return {
        str(key): _flat_names(body.get("ros__parameters") if isinstance(body, dict) else None)
        for key, body in data.items()
    }


def section_hints(
    file: str, sections: dict[str, list[str]], declared: dict[str, Sequence[str]]
) -> list[str]:
    """Return the hints for one params file given to the nodes `declared` (node -> names):
    no key selects any of them, or a selected section sets a parameter the node lacks."""
    if not sections or not declared:
        return []
    nodes = sorted(declared)
    if not any(key_matches(key, node) for key in sections for node in nodes):
        keys = ", ".join(f"'{k}'" for k in sections)
        return [
            f"no top-level key of {file} ({keys}) names a node this started "
            f"({', '.join(nodes)}), so ROS applied nothing: use '{nodes[0]}:' or '/**:'."
        ]
    hints: list[str] = []
    for node in nodes:
        names = [n for key, ns in sections.items() if key_matches(key, node) for n in ns]
        for name in dict.fromkeys(names):
            if name not in declared[node]:
                near = closest(name, declared[node])
                mean = f"; did you mean '{near}'?" if near else "."
                hints.append(
                    f"{node} does not declare '{name}' (set in {file}), so ROS ignored it{mean}"
                )
    return hints


def started_nodes(log_lines: Iterable[str], before: set[str], now: set[str]) -> list[str]:
    """Return the nodes a process started: new in the graph (`now` minus `before`), or named
    by its log lines and running (a node that replaced one of the same name is not new)."""
    logged = {node_name_from_log(line) for line in log_lines} & now
    return sorted((now - before) | logged)


def crash_hint(log_lines: Iterable[str], files: Sequence[str], *, cwd: str = "") -> str | None:
    """Return the hint for a node that a params file stopped at start-up, or None: rcl could
    not open or parse the file (rclpy's RCLError), or a value has the wrong type (rclpy's
    InvalidParameterTypeException). `cwd` is where the node ran (a relative path starts there)."""
    if not _enabled or not files:
        return None
    for line in log_lines:
        found = FILE_TYPE_CRASH.search(line)
        if found:
            name, value, got, expected = found.groups()
            reason = f"Wrong parameter type, expected 'Type.{expected}' got 'Type.{got}'"
            hint = type_hint(reason, name, value)
            return f"in {', '.join(files)}: {hint}" if hint else None
        unread = FILE_UNREAD_CRASH.search(line)
        if unread:
            return _unread_file_hint(unread["file"], unread["error"], cwd)
    return None


def _unread_file_hint(file: str, error: str, cwd: str) -> str:
    """Return the hint for a params file that rcl could not open or parse."""
    if error.startswith("Error opening YAML file"):
        where = f" in {cwd}" if cwd and not os.path.isabs(file) else ""
        folder = os.path.dirname(file) or "."
        return (
            f"there is no file {file}{where} (a relative path starts in the folder the node "
            f"runs in): check its name and folder, for example with `%ls {folder}`."
        )
    line = re.search(r"line(?:_num)? (\d+)", error)
    where = f"rcl stopped reading it at line {line[1]}" if line else f"rcl says: {error}"
    return (
        f"{file} is not a params file ROS can read ({where}): look there for a bracket or "
        "quote left open, a tab, or a line indented differently from its neighbours."
    )


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


def _absolute(name: str) -> str:
    return name if name.startswith("/") else "/" + name


def _param_hint(words: list[str], stdout: str, stderr: str, client: Any) -> str | None:
    """Return the hint for a failed `param get|set|describe NODE NAME [VALUE]`, or None.

    `param describe` of an undeclared name prints nothing at all in Jazzy: that is a mistake
    too, found by asking the node for its parameter names.
    """
    if len(words) < 3 or words[1] not in ("get", "set", "describe", "delete", "dump", "list"):
        return None
    node = _absolute(words[2])
    if stderr.startswith(NODE_NOT_FOUND):
        return _missing_name_hint("node", node, _node_names(client), "`%ros2 node list`")
    if len(words) < 4:
        return None
    name, show = words[3], f"`%ros2 param list {node}`"
    if stderr.startswith(UNDECLARED) or stderr.startswith(PARAMETER_NOT_SET):
        return _missing_name_hint("parameter", name, _parameter_names(client, node), show)
    if words[1] == "describe" and not stdout and not stderr:
        known = _parameter_names(client, node)
        missing = [n for n in words[3:] if known and n not in known]
        return _missing_name_hint("parameter", missing[0], known, show) if missing else None
    if words[1] == "set" and len(words) >= 5:
        return type_hint(stderr, name, words[4])
    return None


def command_hint(
    argv: Sequence[str], stdout: str, stderr: str, client: Callable[[], Any]
) -> str | None:
    """Return one hint for the mistake a `ros2` command line shows in its output, or None.

    Runs only after a failure Jazzy reports, or a `param describe` that printed nothing
    (nothing is asked of the graph otherwise).
    """
    words = _positionals(argv)
    silent_describe = words[:2] == ["param", "describe"] and not stdout
    if not _enabled or not (stderr or silent_describe):
        return None
    value = joined_value(argv)
    if value is not None and "unrecognized arguments" in stderr:
        return split_hint(value)
    if words[:1] == ["param"] and len(words) > 1:
        return _param_hint(words, stdout, stderr, client())
    missing = UNABLE_TO_FIND.search(stderr)
    if words[:2] == ["node", "info"] and missing:
        return _missing_name_hint(
            "node", missing.group(1), _node_names(client()), "`%ros2 node list`"
        )
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
