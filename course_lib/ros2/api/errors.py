"""Errors of the Python API of the `ros2` verbs (the CLI doors print ros2cli's words instead)."""

from __future__ import annotations

import difflib
from collections.abc import Sequence

from ...core.errors import CourseError

__all__ = ["NodeNotFoundError", "ParameterNotSetError", "TopicNotFoundError"]


def _closest(name: str, known: Sequence[str]) -> str:
    match = difflib.get_close_matches(name, list(known), n=1)
    return f"did you mean `{match[0]}`? " if match else ""


class NodeNotFoundError(CourseError):
    """No running node has that name (after waiting for discovery)."""

    def __init__(self, node: str, running: Sequence[str]) -> None:
        listing = ", ".join(running) or "none"
        super().__init__(
            f"Node not found: {node}",
            hint=f"{_closest(node, running)}running nodes: {listing}. "
            "Start the node first (for example `%ros2 run parameter_tests param_vel`).",
        )
        self.node = node


class ParameterNotSetError(CourseError):
    """The node has no parameter of that name."""

    def __init__(self, node: str, name: str, known: Sequence[str]) -> None:
        super().__init__(
            f"Parameter not set: {node} has no parameter '{name}'",
            hint=f"{_closest(name, known)}its parameters: {', '.join(known) or 'none'}.",
        )
        self.node = node
        self.name = name


class TopicNotFoundError(CourseError):
    """No message arrived on a topic, or the topic does not exist."""
