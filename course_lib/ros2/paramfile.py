"""Read a parameter YAML file the way `ros2 param load` does, with errors as ros2cli shows them."""

from __future__ import annotations

import io
import os
from typing import Any

import yaml

from ..core.bounded_yaml import YamlTooLarge, safe_load_bounded
from .results import CommandOutput
from .values import ParamValue, parse_value

__all__ = ["ParamFileError", "read_param_file"]

WILDCARD = "/**"
_TRACEBACK = "Traceback (most recent call last):\n"
_OMITTED = "  (frames of ros2param, rclpy and PyYAML left out by the course)\n"


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
    `at_start`: only the sections a node started with `--params-file` takes (`/**` and its
    own name), as rcl applies them. Raises ParamFileError carrying the real tool's stderr and
    exit code.
    """
    data = _load_yaml(path, cwd)
    merged: dict[Any, Any] = {}
    keys = _section_keys(data, use_wildcard, target_node)
    if at_start:
        keys = [k for k in keys if k == WILDCARD or _is_target(k, target_node)]
    for key in keys:
        section = data[key]
        if not isinstance(section, dict) or "ros__parameters" not in section:
            raise _refusal(f"YAML file is not a valid ROS parameter file for node {key}")
        merged.update(section["ros__parameters"])
    return _flatten("", merged)
