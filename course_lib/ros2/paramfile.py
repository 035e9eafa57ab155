"""Params files, the one place the course reads them: which key selects a node, as rcl
decides it at a node's start; the files a command line gives to `--params-file`; and a file
read the way `ros2 param load` does, with errors as ros2cli shows them.

The rules are rcl's (Jazzy): rcl_yaml_param_parser joins the keys above `ros__parameters:`
with `/` into one node name (`/ns/name:` or `ns: name:`), and rclpy and rclcpp alike prefix a
`/` when it lacks one, make each `/*` in it the regular expression `(/\\w+)` (so `/**` is
`(/\\w+)*`: any name; `/*` one name in the root namespace) and select the node whose fully
qualified name matches it whole; a later section of the node overrides an earlier one.
"""

from __future__ import annotations

import io
import os
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import yaml

from ..core.files.bounded_yaml import YamlTooLarge, safe_load_bounded
from .results import CommandOutput
from .values import ParamValue, parse_value

__all__ = [
    "PARAMS_FILE",
    "PARAMS_KEY",
    "ROS_ARGS",
    "WILDCARD",
    "ParamFileError",
    "Section",
    "key_matches",
    "load_params_text",
    "node_sections",
    "params_files",
    "read_param_file",
    "ros_arguments",
    "sections_for",
]

WILDCARD = "/**"
PARAMS_KEY = "ros__parameters"
_TRACEBACK = "Traceback (most recent call last):\n"
_OMITTED = "  (frames of ros2param, rclpy and PyYAML left out by the course)\n"

# rcl's arguments.c: the flags after `--ros-args` that take the next argument as their value
ROS_ARGS, END_OF_ROS_ARGS, PARAMS_FILE = "--ros-args", "--", "--params-file"
_VALUE_FLAGS = frozenset(
    (PARAMS_FILE, "-p", "--param", "-r", "--remap", "-e", "--enclave", "--log-level")
) | {"--log-file-name", "--log-config-file"}


# --- pure: command lines ----------------------------------------------------------------------
def ros_arguments(argv: Sequence[str]) -> list[tuple[str, str]]:
    """Return the (flag, value) pairs rcl reads from a command line's `--ros-args` blocks.

    As rcl_parse_arguments does: a block starts at `--ros-args` and ends at `--` (another
    `--ros-args` inside it is skipped); `-p`, `-r`, `--params-file`, `-e`, `--log-level`,
    `--log-file-name` and `--log-config-file` take the argument after them, whatever it is;
    a flag with nothing after it gives nothing (rcl refuses the command line).
    """
    pairs: list[tuple[str, str]] = []
    inside, index = False, 0
    while index < len(argv):
        word = argv[index]
        if not inside:
            inside = word == ROS_ARGS
        elif word == END_OF_ROS_ARGS:
            inside = False
        elif word in _VALUE_FLAGS and index + 1 < len(argv):
            pairs.append((word, argv[index + 1]))
            index += 1
        index += 1
    return pairs


def params_files(argv: Sequence[str]) -> list[str]:
    """Return the files a command line gives to `--params-file` (inside `--ros-args`), in
    the order rcl reads them."""
    return [value for flag, value in ros_arguments(argv) if flag == PARAMS_FILE]


# --- pure: which section selects a node -------------------------------------------------------
def key_matches(key: str, node: str) -> bool:
    """Return whether a params file's node name `key` selects the node `node` (`/ns/name`).

    As rclpy and rclcpp match it: `/` prefixed when missing, each `/*` made `(/\\w+)` (so
    `/**` and `**` select every node, `/*` a node in the root namespace, `/ns/*` one in
    `/ns`, `/ns/**` `/ns` itself and every node under it), the rest taken literally.
    """
    name = key if key.startswith("/") else "/" + key
    parts = name.split("/*")
    pattern = re.escape(parts[0]) + "".join(
        r"(/\w+)" + ("*" + re.escape(part[1:]) if part.startswith("*") else re.escape(part))
        for part in parts[1:]
    )
    return re.fullmatch(pattern, "/" + node.lstrip("/"), re.ASCII) is not None


@dataclass(frozen=True)
class Section:
    """One node's section of a params file, named as rcl names it.

    `name`: the keys above `ros__parameters:` joined by `/`; `top`: the file's top-level key
    it sits under; `params`: what `ros__parameters:` holds; `body`: the mapping that holds
    it. A top-level key with no `ros__parameters:` anywhere under it (which rcl refuses) is
    a section too, with `has_params` False and `body` what the key holds.
    """

    name: str
    top: str
    body: Any
    params: Any = None
    has_params: bool = True


class _NodeName:
    """rcl's namespace tracker for node names: keys joined by `/`, the last one removed."""

    def __init__(self) -> None:
        self.text, self.count = "", 0

    def add(self, key: str) -> None:
        joiner = "" if self.count == 0 or self.text.endswith("/") else "/"
        self.text, self.count = self.text + joiner + key, self.count + 1

    def remove(self) -> None:
        if self.count > 0:
            self.count -= 1
            self.text = self.text.rpartition("/")[0] if self.count else ""


def _walk(mapping: dict[Any, Any], depth: int, name: _NodeName, top: str | None) -> list[Section]:
    """Return the sections in a mapping at the node-name level, as rcl's parser walks it."""
    found: list[Section] = []
    for raw, value in mapping.items():
        key, under = str(raw), top if top is not None else str(raw)
        if key.startswith(PARAMS_KEY):  # rcl compares the key's first 15 characters
            if name.count:
                found.append(Section(name.text, under, mapping, value))
            name.remove()
        elif isinstance(value, dict):
            name.add(key)
            found += _walk(value, depth + 1, name, under)
        # a value above `ros__parameters:` (rcl refuses the file): nothing selected there
    if depth == name.count + 1:
        name.remove()
    return found


def node_sections(data: Any) -> list[Section]:
    """Return the node sections of a loaded params file in the order rcl reads them (each
    top-level key that rcl finds no `ros__parameters:` under in its place, as a section
    without parameters); [] for a file that is not a mapping."""
    if not isinstance(data, dict):
        return []
    sections: list[Section] = []
    for key, value in data.items():
        found = _walk({key: value}, 1, _NodeName(), None)
        sections += found or [Section(str(key), str(key), value, has_params=False)]
    return sections


def sections_for(data: Any, node: str) -> list[Section]:
    """Return the sections of a loaded params file that select `node`, in rcl's order (a
    later one overrides an earlier one)."""
    return [section for section in node_sections(data) if key_matches(section.name, node)]


def load_params_text(text: str, name: str = "<params>") -> Any:
    """Return a params file's text loaded as the course loads every params file (an alias
    bomb refused). Raises yaml.YAMLError, or YamlTooLarge (a ValueError)."""
    return safe_load_bounded(text, name=name)


# --- `ros2 param load` and a node's start: the file read, with ros2cli's errors ---------------
class ParamFileError(Exception):
    """The file cannot be loaded; `output` is what ros2cli prints (stderr, exit 1)."""

    def __init__(self, output: CommandOutput) -> None:
        super().__init__(output.stderr.strip())
        self.output = output


def _crash(kind: str, message: str) -> ParamFileError:
    """Return the error for a case where the real tool dies with a traceback."""
    return ParamFileError(CommandOutput("", f"{_TRACEBACK}{_OMITTED}{kind}: {message}\n", 1))


def _refusal(message: str) -> ParamFileError:
    """Return the error for a RuntimeError, which ros2cli prints as one line."""
    return ParamFileError(CommandOutput("", message + "\n", 1))


def _load_yaml(path: str, cwd: str | None) -> Any:
    full = os.path.join(cwd, path) if cwd else path
    try:
        with open(full, encoding="utf-8") as handle:
            text = handle.read()
    except FileNotFoundError:
        raise _crash(
            "FileNotFoundError", f"[Errno 2] No such file or directory: {path!r}"
        ) from None
    except IsADirectoryError:
        raise _crash("IsADirectoryError", f"[Errno 21] Is a directory: {path!r}") from None
    stream = io.StringIO(text)
    stream.name = path  # PyYAML names the file in its messages, as the learner typed it
    try:
        return safe_load_bounded(stream)
    except YamlTooLarge as exc:  # the real tool would hang for minutes: say why at once
        raise _refusal(str(exc)) from None
    except yaml.YAMLError as exc:
        kind = f"{type(exc).__module__}.{type(exc).__name__}"
        raise _crash(kind, str(exc)) from None


def _is_target(key: str, target_node: str | None) -> bool:
    return target_node is not None and "/" + key.lstrip("/") == "/" + target_node.lstrip("/")


def _section_keys(data: Any, use_wildcard: bool, target_node: str | None) -> list[str]:
    if data is None or not hasattr(data, "__contains__"):
        raise _crash("TypeError", f"argument of type '{type(data).__name__}' is not iterable")
    keys = [WILDCARD] if use_wildcard and WILDCARD in data else []
    if not isinstance(data, dict):
        raise _crash("AttributeError", f"'{type(data).__name__}' object has no attribute 'keys'")
    # rclpy walks a set here (order varies run to run); the node's own section last wins.
    others = [k for k in data if k != WILDCARD]
    keys += [k for k in others if not _is_target(k, target_node)]
    keys += [k for k in others if _is_target(k, target_node)]
    if not keys:
        raise _refusal("Param file does not contain selected parameters")
    return keys


def _flatten(prefix: str, tree: dict[Any, Any]) -> list[tuple[str, ParamValue]]:
    flat: list[tuple[str, ParamValue]] = []
    for name, value in tree.items():
        full = f"{prefix}{name}"
        if isinstance(value, dict):
            flat += _flatten(full + ".", value)
        else:
            flat.append((full, parse_value(str(value))))
    return flat


def _start_sections(data: Any, target_node: str | None) -> list[Section]:
    """Return the sections a node started with the file takes: rcl's matching (with no
    node: `/**` alone), in rcl's order."""
    if target_node is None:
        return [s for s in node_sections(data) if s.name in (WILDCARD, WILDCARD[1:])]
    return sections_for(data, target_node)


def read_param_file(
    path: str,
    *,
    use_wildcard: bool = True,
    target_node: str | None = None,
    cwd: str | None = None,
    at_start: bool = False,
) -> list[tuple[str, ParamValue]]:
    """Return the (name, value) pairs `ros2 param load` would send, in its order.

    Values go through `str()` and YAML again, as rclpy does: `velocity: 1` stays an integer.
    `at_start`: only the sections a node started with `--params-file` takes, as rcl selects
    and orders them (see `key_matches`). Raises ParamFileError carrying the real tool's
    stderr and exit code.
    """
    data = _load_yaml(path, cwd)
    keys = _section_keys(data, use_wildcard, target_node)
    merged: dict[Any, Any] = {}
    if at_start:
        for section in _start_sections(data, target_node):
            if not section.has_params or not isinstance(section.params, dict):
                raise _invalid(section.name)
            merged.update(section.params)
        return _flatten("", merged)
    for key in keys:
        section = data[key]
        if not isinstance(section, dict) or PARAMS_KEY not in section:
            raise _invalid(key)
        merged.update(section[PARAMS_KEY])
    return _flatten("", merged)


def _invalid(name: str) -> ParamFileError:
    """Return the error for a selected section without `ros__parameters:` (rclpy's words)."""
    return _refusal(f"YAML file is not a valid ROS parameter file for node {name}")
