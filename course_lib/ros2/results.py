"""Small immutable results shared by the `ros2` verbs, the magics and the Python API (pure)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

__all__ = [
    "CommandOutput",
    "Descriptor",
    "NodeInfo",
    "NodeName",
    "ParamListing",
    "ParamRange",
    "SetResult",
    "TopicInfo",
    "node_name_of",
]


@dataclass(frozen=True)
class CommandOutput:
    """What a `ros2` command printed and how it exited."""

    stdout: str = ""
    stderr: str = ""
    exit_code: int = 0

    @property
    def text(self) -> str:
        """Return stdout then stderr, as a terminal shows them."""
        return self.stdout + self.stderr

    @property
    def ok(self) -> bool:
        """Return whether the command exited with 0."""
        return self.exit_code == 0

    def __add__(self, other: CommandOutput) -> CommandOutput:
        return CommandOutput(
            self.stdout + other.stdout, self.stderr + other.stderr, other.exit_code
        )


class NodeName(NamedTuple):
    """A node's name, namespace and full name (sorts like ros2cli's: by name first)."""

    name: str
    namespace: str
    full_name: str


def node_name_of(full_name: str) -> NodeName:
    """Split `/ns/name` (a leading slash is added if missing) into a NodeName."""
    if not full_name.startswith("/"):
        full_name = "/" + full_name
    namespace, base = full_name.rsplit("/", 1)
    return NodeName(base, namespace or "/", full_name)


class TopicInfo(NamedTuple):
    """A topic (or service/action) name with its type names."""

    name: str
    types: tuple[str, ...]


@dataclass(frozen=True)
class SetResult:
    """The answer of a node to setting (or deleting) one parameter."""

    successful: bool
    reason: str = ""
    name: str = ""


@dataclass(frozen=True)
class ParamRange:
    """A FloatingPointRange or IntegerRange of a descriptor."""

    from_value: float | int
    to_value: float | int
    step: float | int


@dataclass(frozen=True)
class Descriptor:
    """A parameter's descriptor, as `ros2 param describe` shows it."""

    name: str
    type: int
    description: str = ""
    additional_constraints: str = ""
    read_only: bool = False
    dynamic_typing: bool = False
    ranges: tuple[ParamRange, ...] = ()

    @property
    def range(self) -> ParamRange | None:
        """Return the first range (ros2cli shows only that one), or None."""
        return self.ranges[0] if self.ranges else None


@dataclass(frozen=True)
class NodeInfo:
    """What `ros2 node info` lists for one node."""

    name: str
    subscribers: tuple[TopicInfo, ...] = ()
    publishers: tuple[TopicInfo, ...] = ()
    service_servers: tuple[TopicInfo, ...] = ()
    service_clients: tuple[TopicInfo, ...] = ()
    action_servers: tuple[TopicInfo, ...] = ()
    action_clients: tuple[TopicInfo, ...] = ()


@dataclass(frozen=True)
class ParamListing:
    """The parameter names of one node, or why they could not be listed."""

    node: NodeName
    names: tuple[str, ...] | None = None
    types: dict[str, int] = field(default_factory=dict)
    error: str = ""
