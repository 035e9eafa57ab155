"""The register of nodes that lessons started, so that one name never runs twice in a lab.

Kept by the lab's machine service for every kernel of the lab, or by a kernel for itself
outside a lab. A record names a process by its owner tag (pid and start time), so a reused
pid is never mistaken for the node, and nothing but that process is ever signalled.
"""

from __future__ import annotations

import contextlib
import re
import signal
import threading
from dataclasses import asdict, dataclass

from ..core.host.signalling import send
from ..core.waiting import wait_until
from ..processes.orphans import owner_tag

__all__ = ["NodeRecord", "NodeRegister", "node_name_from_log", "stop_tagged"]

_LOG_LINE = re.compile(r"\[[A-Z]+\] \[[0-9.]+\] \[([^\]]+)\]: ")


@dataclass(frozen=True)
class NodeRecord:
    """A node process a lesson started: executable, node name (if known), tag, who started it."""

    executable: str
    node: str
    tag: str
    label: str

    @property
    def alive(self) -> bool:
        return owner_tag(int(self.tag.split(":")[0])) == self.tag

    def as_dict(self) -> dict[str, str]:
        return asdict(self)


def node_name_from_log(text: str) -> str:
    """Return the node name of an rclpy log line (`[INFO] [t] [name]: ...`), or ''."""
    found = _LOG_LINE.search(text)
    return "/" + found.group(1).replace(".", "/") if found else ""


def stop_tagged(tag: str, *, grace_s: float = 5.0) -> bool:
    """Stop the process named by `tag` like Ctrl-C, then SIGTERM, then SIGKILL; True if gone."""
    pid = int(tag.split(":")[0])
    for sig, wait_s in ((signal.SIGINT, grace_s), (signal.SIGTERM, 2.0), (signal.SIGKILL, 2.0)):
        if owner_tag(pid) != tag:
            return True
        reason = "a lesson takes over the node it runs"
        with contextlib.suppress(ProcessLookupError, PermissionError):
            try:  # lessons start nodes as leaders of their own group
                send(pid, sig, group=True, reason=reason)
            except ProcessLookupError:
                send(pid, sig, reason=reason)
        wait_until(lambda: owner_tag(pid) != tag, wait_s)
    return owner_tag(pid) != tag


class NodeRegister:
    """Which lesson runs which node executable; take one over before starting it again."""

    def __init__(self) -> None:
        self._records: dict[str, NodeRecord] = {}
        self._lock = threading.Lock()

    def records(self) -> list[NodeRecord]:
        """Return the records of nodes still running."""
        with self._lock:
            return [r for r in self._records.values() if r.alive]

    def take(self, executable: str) -> NodeRecord | None:
        """Stop the running node of `executable` a lesson started, if any; return its record."""
        with self._lock:
            record = self._records.pop(executable, None)
        if record is None or not record.alive:
            return None
        stop_tagged(record.tag)
        return record

    def stop(self, tag: str) -> NodeRecord | None:
        """Stop the lessons' node whose process `tag` names, if registered; return its record."""
        with self._lock:
            found = [key for key, record in self._records.items() if record.tag == tag]
            record = self._records.pop(found[0]) if found else None
        if record is not None and record.alive:
            stop_tagged(record.tag)
        return record

    def register(self, record: NodeRecord) -> None:
        """Remember that `record`'s process runs `record.executable` now."""
        with self._lock:
            self._records[record.executable] = record
