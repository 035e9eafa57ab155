"""`ros2 launch ... --dry-run`: each node's parameters and where they come from, and traps.

Beyond the real tool. Warns about what real ROS 2 does silently or fails on late: a params
file key that matches no node of the launch, and an integer for a parameter declared double.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

import yaml

from ...core.errors import CourseError
from ..api.actions import IncludeLaunchDescription
from ..core.context import LaunchContext
from ..core.description import AnyLaunchDescriptionSource
from ..ros.declared import DeclaredParameter, declared_parameters
from ..ros.node import UNSPECIFIED_NAME, UNSPECIFIED_NAMESPACE, Node
from ..runtime.shim import launch_modules
from .resolve import parse_launch_arguments, resolve_launch_file

__all__ = ["DryRunReport", "NodePlan", "dry_run", "dry_run_file"]


@dataclass
class NodePlan:
    """One node the launch would start: its name, command and parameters with their origin."""

    node_name: str
    process_name: str
    cmd: list[str]
    values: dict[str, tuple[Any, str]] = field(default_factory=dict)  # name -> (value, origin)
    declared: dict[str, DeclaredParameter] = field(default_factory=dict)


@dataclass
class DryRunReport:
    """What `--dry-run` found: the nodes, launch's own messages, and warnings."""

    path: str
    nodes: list[NodePlan] = field(default_factory=list)
    messages: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    def render(self) -> str:
        """Return the report as text."""
        lines = [f"Dry run of {self.path} (nothing was started)", *self.messages]
        for plan in self.nodes:
            lines += [
                "",
                f"Node {plan.node_name}  (process {plan.process_name})",
                f"  command: {' '.join(plan.cmd)}",
            ]
            for name in sorted(set(plan.values) | set(plan.declared)):
                lines.append("  " + _describe(name, plan))
        lines += ["", "Warnings:" if self.warnings else "No warnings."]
        lines += [f"  - {warning}" for warning in self.warnings]
        return "\n".join(lines) + "\n"


def _describe(name: str, plan: NodePlan) -> str:
    declared = plan.declared.get(name)
    if declared is None:
        where = " (not declared in the node's source)"
    elif declared.file == "rclpy":
        where = f" (declared {declared.type} by rclpy for every node)"
    else:
        where = f" (declared {declared.type} in {declared.file}, line {declared.line})"
    if name in plan.values:
        value, origin = plan.values[name]
        return f"{name} = {value!r}  from {origin}{where}"
    assert declared is not None
    return f"{name} = {declared.default!r}  from the node's default{where}"


def _key_regex(key: str) -> re.Pattern[str]:
    key = "/" + key.lstrip("/")
    pattern = re.escape(key).replace(r"\*\*", ".*").replace(r"\*", "[^/]*")
    return re.compile(pattern + r"\Z")


def _display_name(node: Node) -> str:
    name = node.node_name or ""
    name = name.replace(UNSPECIFIED_NAMESPACE, "")
    return name if UNSPECIFIED_NAME not in name else f"{name} (name set in the node's code)"


def _refuse_aliases(path: str, text: str) -> None:
    """Say what rcl says of an alias in a `--params-file` (the node would not start)."""
    for event in yaml.parse(text, Loader=yaml.SafeLoader):
        if isinstance(event, yaml.AliasEvent):
            line = event.start_mark.line + 1
            raise CourseError(
                f"{path}: Will not support aliasing at line {line}",
                hint="ROS reads --params-file without YAML aliases (*name): write the values out.",
            )


def _file_entries(path: str, fqn: str, seen_keys: list[tuple[str, str]]) -> list[tuple]:
    with open(path) as handle:
        text = handle.read()
    _refuse_aliases(path, text)
    data = yaml.safe_load(text) or {}
    entries = []
    for key, body in data.items():
        seen_keys.append((path, str(key)))
        if _key_regex(str(key)).match(fqn if fqn.startswith("/") else "/" + fqn):
            params = (body or {}).get("ros__parameters", {}) or {}
            for name, value in _flatten(params).items():
                entries.append((name, value, f"{path}, key {key}", "*" not in str(key)))
    return entries


def _flatten(params: dict, prefix: str = "") -> dict[str, Any]:
    flat: dict[str, Any] = {}
    for key, value in params.items():
        name = f"{prefix}{key}"
        flat.update(_flatten(value, name + ".") if isinstance(value, dict) else {name: value})
    return flat


def _plan(node: Node, seen_keys: list[tuple[str, str]]) -> NodePlan:
    spec = node.spec
    assert spec is not None
    fqn = _display_name(node).split(" ")[0]
    plan = NodePlan(
        _display_name(node), spec.name, spec.cmd, declared=declared_parameters(spec.cmd[0])
    )
    entries: list[tuple] = []
    for source in node.parameter_sources:
        if source.kind == "file" and source.path:
            entries += _file_entries(source.path, fqn, seen_keys)
        else:
            origin = {
                "dict": "the launch file's parameters dict",
                "rule": "a Parameter rule",
                "global": "SetParameter",
            }[source.kind]
            entries += [(n, v, origin, True) for n, v in source.values.items()]
    for order, (name, value, origin, specific) in enumerate(entries):
        best = plan.values.get(name)
        rank = (specific, order)
        if best is None or rank >= best[2]:  # type: ignore[misc]
            plan.values[name] = (value, origin, rank)  # type: ignore[assignment]
    plan.values = {k: (v[0], v[1]) for k, v in plan.values.items()}
    return plan


def _warnings(report: DryRunReport, seen_keys: list[tuple[str, str]]) -> None:
    names = [p.node_name.split(" ")[0] for p in report.nodes]
    for path, key in dict.fromkeys(seen_keys):
        if not any(_key_regex(key).match(n) for n in names if n.startswith("/")):
            report.warnings.append(
                f"{path}: key '{key}' matches no node of this launch (nodes: "
                f"{', '.join(names)}); ROS ignores it without a word. Use the node's full name "
                "(e.g. '/param_vel_node') or '/**'."
            )
    for plan in report.nodes:
        for name, (value, origin) in plan.values.items():
            declared = plan.declared.get(name)
            if declared and declared.type == "double" and type(value) is int:
                report.warnings.append(
                    f"{plan.node_name}: '{name}' is declared double ({declared.file}, line "
                    f"{declared.line}) but {origin} gives the integer {value}: the node will "
                    f"refuse it and exit. Write {float(value)}."
                )
            elif declared is None and plan.declared:
                report.warnings.append(
                    f"{plan.node_name}: '{name}' (from {origin}) is not declared by the node; "
                    "it is ignored unless the node allows undeclared parameters."
                )


def dry_run_file(path: str, launch_arguments: list[tuple[str, str]]) -> DryRunReport:
    """Evaluate a launch file without starting anything; report nodes and parameters."""
    context = LaunchContext()
    pending: list[Any] = [
        IncludeLaunchDescription(
            AnyLaunchDescriptionSource(path), launch_arguments=launch_arguments
        )
    ]
    with launch_modules():
        while pending:
            entity = pending.pop(0)
            pending = list(entity.visit(context) or []) + pending
    messages = [f"[{level}] [{logger}]: {text}" for logger, level, text in context.messages]
    report = DryRunReport(path, messages=messages)
    seen_keys: list[tuple[str, str]] = []
    report.nodes = [_plan(p, seen_keys) for p in context.planned_processes if isinstance(p, Node)]
    _warnings(report, seen_keys)
    report.warnings += [
        f"reading this launch file ran {code} (as `ros2 launch` does: read a launch file "
        "from someone you trust only)"
        for code in dict.fromkeys(context.code_run)
    ]
    return report


def dry_run(package_or_path: str, file: str | None = None, *launch_args: str) -> DryRunReport:
    """Return what `ros2 launch ... --dry-run` prints (`print(report.render())`)."""
    path, arguments = resolve_launch_file(package_or_path, file, list(launch_args))
    return dry_run_file(path, parse_launch_arguments(arguments))
