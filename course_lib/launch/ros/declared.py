"""Which parameters a node declares, and their types, read statically from its Python source.

Reading the source (with `ast`) never starts the node, works before the ROS graph exists and
cannot hang; it finds `declare_parameter('name', default, ...)` calls with literal names and
defaults, which is how tutorial nodes declare parameters. Anything else is simply unknown.
"""

from __future__ import annotations

import ast
import importlib.metadata
import os
import re
from dataclasses import dataclass
from pathlib import Path

__all__ = ["DeclaredParameter", "declared_parameters", "node_sources"]


@dataclass(frozen=True)
class DeclaredParameter:
    """A parameter a node declares: name, type (ROS words), default, where."""

    name: str
    type: str
    default: object
    file: str
    line: int


def _type_of(value: object) -> str:
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "double"
    if isinstance(value, str):
        return "string"
    if isinstance(value, list) and value:
        return _type_of(value[0]) + " array"
    return "unknown"


def _search_dirs(executable: Path) -> list[Path]:
    prefix = executable.parents[2]
    dirs = [Path(p) for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    for site in prefix.glob("lib/python*/site-packages"):
        dirs.append(site)
        for link in site.glob("*.egg-link"):
            dirs.append(Path(link.read_text().splitlines()[0].strip()))
    return [d for d in dirs if d.is_dir()]


def _entry_point_module(text: str, executable: Path) -> Path | None:
    match = re.search(r"'([^']+)',\s*'console_scripts',\s*'([^']+)'", text)
    if not match:
        return None
    dirs = _search_dirs(executable)
    for dist in importlib.metadata.distributions(path=[str(d) for d in dirs]):
        for entry in dist.entry_points:
            if entry.group == "console_scripts" and entry.name == match.group(2):
                relative = Path(*entry.module.split("."))
                for folder in dirs:
                    for candidate in (
                        folder / f"{relative}.py",
                        folder / relative / "__init__.py",
                    ):
                        if candidate.is_file():
                            return candidate
    return None


def node_sources(executable: str) -> list[Path]:
    """Return the Python files that make up a node executable (empty when not Python)."""
    path = Path(executable)
    try:
        text = path.read_text(errors="strict")[:20000]
    except (OSError, UnicodeDecodeError):
        return []
    module = _entry_point_module(text, path)
    if module is not None:
        return [module]
    scripts = [
        Path(m)
        for m in re.findall(r"[\"']?(/\S+?\.py)[\"']?", text.split("\n", 1)[0] + "\n" + text)
        if Path(m).is_file()
    ]
    if scripts and not text.startswith("#!/usr/bin/env python"):
        return scripts[:1]
    return [path] if text.startswith("#!") and "python" in text.split("\n", 1)[0] else []


def _literal(node: ast.AST) -> object:
    try:
        return ast.literal_eval(node)
    except (ValueError, SyntaxError, TypeError):
        return None


# Every rclpy node of Jazzy declares these itself (see `ros2 param list` of any node).
RCLPY_BUILTINS = (
    DeclaredParameter("start_type_description_service", "bool", True, "rclpy", 0),
    DeclaredParameter("use_sim_time", "bool", False, "rclpy", 0),
)


def declared_parameters(executable: str) -> dict[str, DeclaredParameter]:
    """Return the parameters the executable's source declares, by name."""
    found: dict[str, DeclaredParameter] = {}
    sources = node_sources(executable)
    if sources:  # a node whose source we can read is an rclpy node
        found.update({p.name: p for p in RCLPY_BUILTINS})
    for source in sources:
        try:
            tree = ast.parse(source.read_text(), str(source))
        except (OSError, SyntaxError, ValueError):
            continue
        for call in ast.walk(tree):
            if not (
                isinstance(call, ast.Call)
                and isinstance(call.func, ast.Attribute)
                and call.func.attr == "declare_parameter"
                and call.args
            ):
                continue
            name = _literal(call.args[0])
            if isinstance(name, str):
                default = _literal(call.args[1]) if len(call.args) > 1 else None
                found[name] = DeclaredParameter(
                    name, _type_of(default), default, str(source), call.lineno
                )
    return found
