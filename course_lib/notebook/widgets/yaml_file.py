"""Parameter files and `ros2 param set` lines from Python values (pure)."""

from __future__ import annotations

import shlex
from pathlib import Path
from typing import Any

import yaml

from ...core.files.atomic_files import atomic_write

__all__ = ["cli_value", "params_yaml", "set_command", "write_params_file"]


def cli_value(value: Any) -> str:
    """Return `value` as typed on a `ros2 param set` line (YAML rules: 0.2 double, 1 integer)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, int):
        return str(value)
    text = yaml.safe_dump(value, default_flow_style=True, width=1 << 16).strip()
    return text.removesuffix("...").strip()


def set_command(node: str, name: str, value: Any) -> str:
    """Return the `ros2 param set` line that sets `name` of `node` to `value`, quoted for a
    shell: pasted into a terminal, it sets exactly `value` (spaces and quotes included)."""
    words = ("ros2", "param", "set", node, name, cli_value(value))
    return " ".join(shlex.quote(word) for word in words)


def params_yaml(node: str, values: dict[str, Any]) -> str:
    """Return a params file: `node:` then `ros__parameters:` then the values, sorted."""
    data = {node: {"ros__parameters": dict(sorted(values.items()))}}
    return yaml.safe_dump(data, default_flow_style=False, sort_keys=False)


def write_params_file(path: Path, node: str, values: dict[str, Any]) -> Path:
    """Write the params file atomically (a reader never sees half of it); return the path."""
    return atomic_write(path, params_yaml(node, values))
