"""What the learner asked of a node since an exercise was armed: its `param set` requests.

Read from the lab's parameter journal, which every door of the course writes (a `%ros2` cell, a
terminal's `ros2`, the panel), with whether the node refused each: a verdict can then name the
value the learner typed, not only what the node holds now.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ...core.param_journal import read_journal

__all__ = ["Request", "learner_requests"]


@dataclass(frozen=True)
class Request:
    """One `param set` the learner sent to the node since the exercise was armed."""

    name: str
    text: str  # the value as the learner typed it: `5`, `5.0`
    type_name: str  # as ROS read it: integer, double, string...
    value: Any
    refused: bool


def learner_requests(
    domain: int | str, since: float, node: str, *, checker: str = ""
) -> list[Request]:
    """Return the `param set` requests to `node` since wall time `since`, and whether it
    refused each; requests sent through the door named `checker` (the exercise's own) are
    left out."""
    from ...notebook.history import format_value
    from ...ros2.values import from_journal

    records = read_journal(domain)
    failed = {r.get("id") for r in records if r.get("t") == "failed"}
    found = []
    for record in records:
        if record.get("t") != "set" or record.get("node") != node:
            continue
        if (checker and record.get("door") == checker) or record.get("wall", 0.0) < since:
            continue
        value = from_journal(record.get("value"))
        if value is not None:
            text, refused = format_value(value), record.get("id") in failed
            name = str(record.get("name"))
            found.append(Request(name, text, value.type_name, value.python, refused))
    return found
