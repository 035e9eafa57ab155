"""The pure hints of a params file given to nodes at start-up: a top-level key that selects no
node, or a parameter the node does not declare (read as rcl reads keys: `/**`, `*` patterns)."""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterable, Sequence
from typing import Any

import yaml

from ..core.bounded_yaml import safe_load_bounded
from ..lab.register import node_name_from_log
from .value_hints import closest

__all__ = ["file_sections", "key_matches", "params_files", "section_hints", "started_nodes"]


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
