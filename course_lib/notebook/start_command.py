"""The `%ros2 run` line that started a node last in a lab, from the lab's parameter journal:
what a widget or a hint offers when that node has stopped."""

from __future__ import annotations

import shlex
from typing import Any

from ..core import ament
from ..core.param_journal import read_journal

__all__ = ["last_start_command"]


def _started(records: list[dict[str, Any]], node: str) -> dict[str, Any] | None:
    """Return the last start record of `node`: named in it, or by the next `named` record of
    its executable (a notebook's door learns the name from the node's log)."""
    found = None
    unnamed: dict[Any, dict[str, Any]] = {}  # executable -> its last start, not named yet
    for record in records:
        kind, executable = record.get("t"), record.get("exe")
        if kind == "start" and record.get("node"):
            found = record if record["node"] == node else found
        elif kind == "start":
            unnamed[executable] = record
        elif kind == "named" and executable in unnamed:
            start = unnamed.pop(executable)
            found = start if record.get("node") == node else found
    return found


def last_start_command(node: str, domain: int | str, env: Any = None) -> str | None:
    """Return the `%ros2 run` line that started `node` last in the lab of ROS domain `domain`
    (from the parameter journal), or None if the course did not start it that way (a launch
    file, a terminal, unknown)."""
    record = _started(read_journal(domain), node)
    if record is None or record.get("door") in ("launch", "terminal"):
        return None
    executable = str(record.get("exe") or "")
    package = ament.package_of_executable(executable, env) if executable else None
    if package is None:
        return None
    args = [str(a) for a in record.get("args") or []]
    words = ["%ros2", "run", package, executable, *(["--ros-args", *args] if args else [])]
    return " ".join(shlex.quote(word) for word in words)
