"""The pure hints of a params file given to nodes at start-up: a key that selects no node, or
a parameter the node does not declare. Which key selects which node, and which files a command
line gives, are rcl's rules, kept in `ros2/paramfile.py`."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import yaml

from ..lab.register import node_name_from_log
from ..ros2.paramfile import key_matches, load_params_text, node_sections
from .value_hints import closest

__all__ = ["file_sections", "section_hints", "started_nodes"]


# --- pure: params files --------------------------------------------------------------------
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
    """Return each node section of a params file (named as rcl names it: `/ns/name:` or
    `ns: name:`, a top-level key without `ros__parameters:` as it stands) with the parameter
    names under it (empty on a file that is not a mapping: ROS itself reports those)."""
    try:
        data = load_params_text(text, name=name) if text.strip() else None
    except (yaml.YAMLError, ValueError):
        return {}
    sections: dict[str, list[str]] = {}
    for section in node_sections(data):
        names = sections.setdefault(section.name, [])  # rcl merges a name written twice
        names += [n for n in _flat_names(section.params) if n not in names]
    return sections


def section_hints(
    file: str, sections: dict[str, list[str]], declared: Mapping[str, Sequence[str]]
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
