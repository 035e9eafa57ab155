"""`lesson.reset(node)` and `lesson.diff(node, path)`: back to the start-up values, and what
differs from them (or from a params file), in `ros2 param dump`'s own YAML.

The start-up values come from the node's history (notebook/history.py): the value each
parameter had before its first change, or the override it was started with.
"""

from __future__ import annotations

import difflib
import os
from dataclasses import dataclass

from ..core.errors import CourseError
from ..core.param_journal import acting_door
from ..ros2 import render
from ..ros2.values import ParamValue
from .history import ParameterHistory, format_value, node_history

__all__ = ["ParamDiff", "ResetReport", "diff_parameters", "reset_parameters"]


def _full(node: str) -> str:
    return node if node.startswith("/") else "/" + node


def _running(node: str) -> dict[str, ParamValue]:
    """Return the node's current values by name (as `ros2 param dump` asks for them)."""
    from ..ros2.api import nodes_and_params as api

    names = api.param_list(node)
    return dict(zip(names, api.client().get_parameters(node, names), strict=False))


def _startup(history: ParameterHistory, running: dict[str, ParamValue]) -> dict[str, ParamValue]:
    """Return the start-up value of every parameter the history knows one for."""
    names = [*history.changed_names(), *(n for n, _v, _s in history.overrides)]
    known = {n: history.startup_value(n) for n in dict.fromkeys(names)}
    return {n: v for n, v in known.items() if v is not None}


@dataclass(frozen=True)
class ResetReport:
    """What `lesson.reset` changed (plain text, the same on every run)."""

    node: str
    lines: tuple[str, ...]

    def __repr__(self) -> str:
        if not self.lines:
            return f"Nothing to reset: {self.node} runs with its start-up values.\n"
        head = f"Reset {self.node} to its start-up values:"
        return "\n".join([head, *(f"  {line}" for line in self.lines)]) + "\n"


def reset_parameters(node: str, domain: int | str) -> ResetReport:
    """Set every parameter changed since the node started back to its start-up value."""
    from ..ros2.api import nodes_and_params as api

    full = _full(node)
    history = node_history(full, domain)
    running = _running(full)
    lines = []
    for name in history.changed_names():
        target = history.startup_value(name)
        if target is None:
            lines.append(f"{name}: its start-up value is unknown (changed before any lesson ran)")
        elif name in running and running[name] != target:
            with acting_door("lesson.reset"):
                result = api.param_set(full, name, target)
            was, now = format_value(running[name]), format_value(target)
            lines.append(
                f"{name}: {was} → {now}"
                if result.successful
                else f"{name}: refused by the node ({result.reason})"
            )
    for name, target in _startup(history, running).items():
        if name not in history.changed_names() and running.get(name, target) != target:
            with acting_door("lesson.reset"):
                result = api.param_set(full, name, target)
            if result.successful:
                lines.append(f"{name}: {format_value(running[name])} → {format_value(target)}")
    return ResetReport(full, tuple(lines))


@dataclass(frozen=True)
class ParamDiff:
    """Two `ros2 param dump` texts of one node and their line-by-line difference."""

    node: str
    left_label: str
    left: str
    right: str

    @property
    def same(self) -> bool:
        """Return whether the running values are the compared ones."""
        return self.left == self.right

    def __repr__(self) -> str:
        if self.same:
            return f"No difference: {self.node} runs with the values of {self.left_label}.\n"
        lines = difflib.unified_diff(
            self.left.splitlines(),
            self.right.splitlines(),
            fromfile=self.left_label,
            tofile=f"{self.node} (running)",
            n=100,
            lineterm="",
        )
        return "\n".join(line for line in lines if not line.startswith("@@")) + "\n"


def _dump(node: str, values: dict[str, ParamValue]) -> str:
    return render.param_dump(node, sorted(values.items())).stdout.rstrip("\n") + "\n"


def diff_parameters(
    node: str, domain: int | str, path: str | os.PathLike[str] | None = None
) -> ParamDiff:
    """Compare the running values with a params file (or the start-up values when no path).

    Raises CourseError (with Jazzy's own message) when the file cannot be read.
    """
    from ..ros2.paramfile import ParamFileError, read_param_file

    full = _full(node)
    running = _running(full)
    if path is None:
        expected = {**running, **_startup(node_history(full, domain), running)}
        label = "start-up values"
    else:
        try:
            loaded = read_param_file(str(path), target_node=full, at_start=True)
        except ParamFileError as exc:
            raise CourseError(
                f"{path} is not a params file for {full}:\n{exc.output.stderr.strip()}",
                hint=f"compare with a file `ros2 param dump {full}` wrote, or fix the line named.",
            ) from None
        expected = {**running, **dict(loaded)}
        label = str(path)
    return ParamDiff(full, label, _dump(full, expected), _dump(full, running))
