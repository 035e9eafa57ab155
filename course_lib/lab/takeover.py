"""One node of each name in a lab: a lesson stops what another lesson left running first.

`%ros2 run`, `lesson.run()` and `lesson.launch()` call `take_over()` before they start a node
and `remember()` after; in a lab the lab's register is asked (every kernel shares it), outside
a lab this kernel's own. A node the learner starts in a terminal is not the lessons' business:
duplicates made on purpose behave as on a real ROS 2 machine.

When a lesson's new driver stops another lesson's node (`keep_one_driver`), a `stopped` record
in the lab's parameter journal says so, for every kernel: `stopped_by_a_lesson()` reads it when
a command no longer finds that node.
"""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass

from ..core import param_journal
from ..core.host import procfs
from ..processes.children import ChildProcess, OutputLine
from ..processes.orphans import owner_tag
from .client import machine_client
from .register import NodeRecord, NodeRegister, node_name_from_log

__all__ = [
    "StoppedNode",
    "keep_one_driver",
    "lessons_nodes",
    "remember",
    "set_label",
    "stopped_by_a_lesson",
    "take_over",
]

_local = NodeRegister()
_state = {"label": "this notebook"}
_lock = threading.Lock()


def set_label(label: str) -> None:
    """Name who starts nodes from this kernel from now on (`lesson 7`)."""
    with _lock:
        _state["label"] = label


def _label() -> str:
    with _lock:
        return _state["label"]


def take_over(executable: str) -> str:
    """Stop a lessons' node of `executable` still running; return the line saying so, or ''."""
    client = machine_client()
    if client is not None:
        found = client.request("node.take", executable=executable).get("stopped")
        record = NodeRecord(**found) if found else None
    else:
        record = _local.take(executable)
    if record is None:
        return ""
    node = record.node or executable
    return (
        f"Stopped {node} ({executable}) that {record.label} had started: "
        "one node of each name runs in your lab."
    )


def remember(child: ChildProcess, executable: str) -> None:
    """Register `child` as the lessons' running `executable` (its node name from its log)."""
    label = _label()
    node = next((n for n in map(node_name_from_log, (ln.text for ln in child.lines)) if n), "")
    _register(child, executable, node, label)
    if node:
        return

    def learn_name(line: OutputLine) -> None:  # a slow node logs its name later
        name = node_name_from_log(line.text)
        if name:
            child.remove_listener(learn_name)
            _register(child, executable, name, label)

    child.add_listener(learn_name)


def _register(child: ChildProcess, executable: str, node: str, label: str) -> None:
    if not child.alive:
        return
    record = NodeRecord(executable, node, owner_tag(child.pid), label)
    if node:  # the parameter journal's start record named the executable only
        # the node's own domain (its start record's), not this process's current one
        domain = procfs.environ(child.pid).get("ROS_DOMAIN_ID") or os.environ.get("ROS_DOMAIN_ID")
        param_journal.append(domain, {"t": "named", "exe": executable, "node": node})
    client = machine_client()
    if client is not None:
        client.request(
            "node.register",
            executable=record.executable,
            node=record.node,
            tag=record.tag,
            label=record.label,
        )
    else:
        _local.register(record)


def lessons_nodes() -> list[NodeRecord]:
    """Return the nodes lessons started that still run (the lab's, or this kernel's)."""
    client = machine_client()
    if client is None:
        return _local.records()
    return [NodeRecord(**found) for found in client.request("node.list").get("nodes", [])]


def _stop(record: NodeRecord) -> None:
    client = machine_client()
    if client is not None:
        client.request("node.stop", tag=record.tag)
    else:
        _local.stop(record.tag)


def _domain(pid: int) -> str | None:
    """Return the ROS domain of process `pid` (its start environment's), else this one's."""
    return procfs.environ(pid).get("ROS_DOMAIN_ID") or os.environ.get("ROS_DOMAIN_ID")


def keep_one_driver(child: ChildProcess) -> str:
    """If `child` drives the robot, stop the lessons' other drivers; return what to say.

    Each node stopped is recorded in the journal (who stopped it, for which node), so that a
    lesson that still counts on it can say why it is gone.
    """
    from ..ros2.api.nodes_and_params import client
    from .drivers import one_driver

    if not child.alive:
        return ""
    names = (node_name_from_log(line.text) for line in child.lines)
    started = next((n for n in names if n), "") or child.name
    by, domain = _label(), _domain(child.pid)

    def stop(record: NodeRecord) -> None:
        _stop(record)
        param_journal.append(
            domain,
            {"t": "stopped", "exe": record.executable, "node": record.node,
             "started_by": record.label, "by": by, "for": started},
        )  # fmt: skip

    return "\n".join(one_driver(client(), child.pid, lessons_nodes(), stop))


@dataclass(frozen=True)
class StoppedNode:
    """A lessons' node another lesson stopped, as the journal records it."""

    node: str
    executable: str
    started_by: str  # who had started it (`lesson 7`)
    by: str  # who stopped it (`lesson 11`)
    started: str  # the node whose start stopped it (`/descriptor_vel_node`)


def _restarts(record: dict[str, object], node: str, executable: object) -> bool:
    """Return whether a journal record starts `node` (or its executable) again."""
    kind = record.get("t")
    return (kind == "named" and record.get("node") == node) or (
        kind == "start" and record.get("exe") == executable
    )


def stopped_by_a_lesson(node: str, domain: int | str | None) -> StoppedNode | None:
    """Return the lesson that stopped `node` if the journal's last word on it says so (no
    start of it since); None when the records cannot tell."""
    if domain is None:
        return None
    last: dict[str, object] | None = None
    for record in param_journal.read_journal(domain):
        if record.get("t") == "stopped" and record.get("node") == node:
            last = record
        elif last is not None and _restarts(record, node, last.get("exe")):
            last = None
    if last is None:
        return None
    fields = ("exe", "started_by", "by", "for")
    return StoppedNode(node, *(str(last.get(f) or "") for f in fields))
