"""Turn results into the exact text ROS 2 Jazzy's `ros2` verbs print (pure: data in, text out)."""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from typing import Any

import yaml

from .results import CommandOutput, Descriptor, NodeInfo, ParamListing, SetResult, TopicInfo
from .values import GET_LABELS, NOT_SET, ParamValue, type_name

__all__ = [
    "failure",
    "node_info",
    "node_list",
    "param_delete",
    "param_describe",
    "param_dump",
    "param_get",
    "param_list",
    "param_load",
    "param_set",
    "topic_list",
]


def failure(message: str) -> CommandOutput:
    """Return what ros2cli does when a verb returns an error string: stderr line, exit 1."""
    return CommandOutput("", message + "\n", 1)


def _lines(lines: Iterable[str]) -> str:
    return "".join(f"{line}\n" for line in lines)


def param_list(
    listings: Iterable[ParamListing],
    *,
    single_node: bool,
    regex: str | None = None,
    with_types: bool = False,
) -> CommandOutput:
    """Render `ros2 param list [node]`: nodes sorted as ros2cli sorts them (by name first)."""
    out: list[str] = []
    pattern = re.compile(regex) if regex is not None else None
    for listing in sorted(listings, key=lambda entry: tuple(entry.node)):
        if listing.names is None:
            out.append(
                "Wait for service timed out waiting for parameter services for node "
                f"{listing.node!r}"
            )
            continue
        names = sorted(listing.names)
        if pattern is not None:
            names = [name for name in names if pattern.match(name)]
        if not single_node and names:
            out.append(f"{listing.node.full_name}:")
        for name in names:
            if with_types:
                out.append(f"  {name} (type: {type_name(listing.types[name])})")
            else:
                out.append(f"  {name}")
    return CommandOutput(_lines(out))


def param_get(value: ParamValue | None, *, hide_type: bool = False) -> CommandOutput:
    """Render `ros2 param get`; None means the node answered with no value."""
    if value is None:
        return failure("Parameter not set")
    shown = None if value.type == NOT_SET else value.python
    if hide_type:
        return CommandOutput(f"{shown}\n")
    label = GET_LABELS.get(value.type, "Parameter not set.")
    return CommandOutput(f"{label} {shown}\n" if shown is not None else f"{label}\n")


def _set_line(result: SetResult, ok: str, failed: str) -> CommandOutput:
    msg = ok if result.successful else failed
    if result.reason:
        msg += ": " + result.reason
    if result.successful:
        return CommandOutput(msg + "\n")
    return CommandOutput("", msg + "\n")


def param_set(result: SetResult) -> CommandOutput:
    """Render `ros2 param set`; a refused value goes to stderr but still exits 0."""
    return _set_line(result, "Set parameter successful", "Setting parameter failed")


def param_delete(result: SetResult) -> CommandOutput:
    """Render `ros2 param delete`."""
    return _set_line(result, "Deleted parameter successfully", "Deleting parameter failed")


def param_load(results: Sequence[SetResult]) -> CommandOutput:
    """Render `ros2 param load`: one line per parameter, failures on stderr, exit 0."""
    output = CommandOutput()
    for result in results:
        prefix = f"Set parameter {result.name}"
        output += _set_line(result, f"{prefix} successful", f"{prefix} failed")
    return output


def _describe_lines(descriptor: Descriptor) -> list[str]:
    lines = [f"Parameter name: {descriptor.name}", f"  Type: {type_name(descriptor.type)}"]
    if descriptor.description:
        lines.append(f"  Description: {descriptor.description}")
    lines.append("  Constraints:")
    if descriptor.read_only:
        lines.append("    Read only: true")
    if descriptor.range is not None:
        lines.append(f"    Min value: {descriptor.range.from_value}")
        lines.append(f"    Max value: {descriptor.range.to_value}")
        if descriptor.range.step:
            lines.append(f"    Step: {descriptor.range.step}")
    if descriptor.additional_constraints:
        lines.append(f"    Additional constraints: {descriptor.additional_constraints}")
    return lines


def param_describe(descriptors: Iterable[Descriptor]) -> CommandOutput:
    """Render `ros2 param describe` for one or more descriptors."""
    return CommandOutput(_lines(line for d in descriptors for line in _describe_lines(d)))


def _insert(tree: dict[str, Any], name: str, value: Any) -> None:
    head, dot, rest = name.partition(".")
    if dot:
        _insert(tree.setdefault(head, {}), rest, value)
    else:
        tree[name] = value


def dump_tree(node_full_name: str, values: Iterable[tuple[str, ParamValue]]) -> dict[str, Any]:
    """Return the mapping `ros2 param dump` writes (dotted names nested)."""
    params: dict[str, Any] = {}
    for name, value in values:
        _insert(params, name, value.python)
    return {node_full_name: {"ros__parameters": params}}


def param_dump(node_full_name: str, values: Iterable[tuple[str, ParamValue]]) -> CommandOutput:
    """Render `ros2 param dump`: sorted YAML and the blank line `print` adds."""
    text = yaml.dump(dump_tree(node_full_name, values), default_flow_style=False)
    return CommandOutput(text + "\n")


def node_list(full_names: Iterable[str], *, count_only: bool = False) -> CommandOutput:
    """Render `ros2 node list [--count-nodes]`, warning about duplicate names."""
    names = sorted(full_names)
    if count_only:
        return CommandOutput(f"{len(names)}\n")
    err = ""
    if len(set(names)) < len(names):
        err = (
            "WARNING: Be aware that there are nodes in the graph that share an exact name, "
            "which can have unintended side effects.\n"
        )
    return CommandOutput(_lines(names), err)


def _section(title: str, entries: Sequence[TopicInfo]) -> list[str]:
    body = "\n".join(f"    {e.name}: {', '.join(e.types)}" for e in entries)
    return [f"  {title}:", body]


def node_info(info: NodeInfo, *, duplicates: int = 1) -> CommandOutput:
    """Render `ros2 node info` (an empty section prints an empty line, as ros2cli does)."""
    err = ""
    if duplicates > 1:
        err = (
            f'There are {duplicates} nodes in the graph with the exact name "{info.name}". '
            "You are seeing information about only one of them.\n"
        )
    lines = [info.name]
    lines += _section("Subscribers", info.subscribers)
    lines += _section("Publishers", info.publishers)
    lines += _section("Service Servers", info.service_servers)
    lines += _section("Service Clients", info.service_clients)
    lines += _section("Action Servers", info.action_servers)
    lines += _section("Action Clients", info.action_clients)
    return CommandOutput(_lines(lines), err)


def topic_list(
    topics: Sequence[TopicInfo], *, show_types: bool = False, count_only: bool = False
) -> CommandOutput:
    """Render `ros2 topic list [-t] [-c]` in the graph's order."""
    if count_only:
        return CommandOutput(f"{len(topics)}\n")
    if show_types:
        return CommandOutput(_lines(f"{t.name} [{', '.join(t.types)}]" for t in topics))
    return CommandOutput(_lines(t.name for t in topics))
