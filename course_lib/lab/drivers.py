"""One driver for the robot: of the nodes lessons start, one at a time publishes on /cmd_vel.

After a lesson starts a node, `one_driver()` looks at who publishes on /cmd_vel. When the new
node is one of them, every other node a lesson started that publishes there is stopped (one
line says which); a publisher the learner started in a terminal is theirs: it keeps running
and is named, with how to stop it. The self-checks ask `other_drivers()`, so that a second
publisher fails a check for that reason, never with a wrong-answer message.

Which process holds a publisher: Fast DDS writes the low 16 bits of the pid into bytes 4 and 5
of the participant's GUID prefix (after the vendor id 01.0f and two bytes of host id).
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import psutil

__all__ = [
    "CMD_VEL",
    "GONE_WAIT_S",
    "Publisher",
    "describe",
    "one_driver",
    "other_drivers",
    "pid_bits",
]

CMD_VEL = "/cmd_vel"
_EPROSIMA = (0x01, 0x0F)
_SEEN_WAIT_S = 1.0  # at most, until a publisher started moments ago is discovered
# At most, until a new node's /rosout publisher is discovered (LOCALHOST discovery takes up to
# ~3 s on a busy host); the wait ends as soon as it is, so a quiet host waits ~0.1 s.
_NEW_NODE_WAIT_S = 5.0
# After a new node answered (its constructor is done): until its publishers are discovered.
_ANNOUNCED_S = 0.5
# At most, until what a process that has just ended left in the graph (its endpoints, its
# node's name) is gone: a little past the discovery lease of course_lib/dds/fastdds_profile.xml
GONE_WAIT_S = 3.5
_POLL_S = 0.02
_DAEMON = "course_lib.ros2.command.daemon"


def pid_bits(gid: Sequence[int]) -> int | None:
    """Return the low 16 bits of the pid of the process that owns a DDS endpoint, if known."""
    if tuple(gid[:2]) != _EPROSIMA or len(gid) < 6:
        return None
    return gid[4] | gid[5] << 8


def _in_tree(pid: int, root: int) -> bool:
    """Return True if process `pid` is `root` or one of its descendants."""
    if pid == root:
        return True
    try:
        return any(parent.pid == root for parent in psutil.Process(pid).parents())
    except psutil.Error:
        return False


@dataclass(frozen=True)
class Publisher:
    """A publisher of a topic: its node's full name and the processes that may hold it."""

    node: str
    pids: tuple[int, ...]

    def runs_in(self, root: int) -> bool:
        """Return True if the publisher's process is `root` or a descendant of it."""
        return any(_in_tree(pid, root) for pid in self.pids)


def _full_name(namespace: str, name: str) -> str:
    return namespace.rstrip("/") + "/" + name


def _mine(pid: int) -> bool:
    """Return True for this user's process, unless it is the course's `ros2` daemon (whose
    node publishes for a terminal's `ros2 topic pub`: Ctrl-C there stops it, not a kill)."""
    try:
        process = psutil.Process(pid)
        return process.uids().real == os.getuid() and _DAEMON not in process.cmdline()
    except psutil.Error:
        return False


def publishers(client: Any, topic: str = CMD_VEL) -> list[Publisher]:
    """Return the publishers of `topic` that `client` (a RosClient) has discovered."""
    live = psutil.pids()
    found = []
    for info in client.node.get_publishers_info_by_topic(topic):
        bits = pid_bits(info.endpoint_gid)
        pids = () if bits is None else tuple(p for p in live if p & 0xFFFF == bits and _mine(p))
        found.append(Publisher(_full_name(info.node_namespace, info.node_name), pids))
    return found


def _drives(client: Any, root: int) -> bool:
    """Return whether the node(s) of process `root` publish /cmd_vel, once discovered.

    Every rclpy node publishes /rosout from its first moment, but makes its other publishers
    later in its constructor (descriptor_vel declares three parameters first: on a busy host
    its /rosout was seen before its /cmd_vel existed). A node answers requests only once it
    spins, after its constructor: once it has answered, its publishers exist, and their
    announcements follow within _ANNOUNCED_S.
    """
    deadline = time.monotonic() + _NEW_NODE_WAIT_S
    answered_at: float | None = None
    while True:
        if any(p.runs_in(root) for p in publishers(client)):
            return True
        now = time.monotonic()
        if now >= deadline or (answered_at is not None and now - answered_at >= _ANNOUNCED_S):
            return False
        if answered_at is None:
            nodes = [p.node for p in publishers(client, "/rosout") if p.runs_in(root)]
            if nodes:
                client.answers(nodes[0], timeout=deadline - now)  # or not: the deadline holds
                answered_at = time.monotonic()
                continue
        time.sleep(_POLL_S)


def describe(publisher: Publisher) -> str:
    """Return how to name a publisher to the learner: its node, and its pid if known."""
    return publisher.node + (f" (pid {publisher.pids[0]})" if len(publisher.pids) == 1 else "")


def other_drivers(client: Any, own: int | None) -> list[Publisher]:
    """Return the publishers of /cmd_vel outside process `own`'s tree (all if `own` is None).

    A publisher no live process of this user holds may be one that has just ended (its
    endpoints stay in the graph until its discovery lease runs out): it is given that long to
    leave before it counts (another account's publisher stays, and counts).
    """
    from ..core.waiting import wait_until

    client.wait_all_seen(timeout=_SEEN_WAIT_S)  # a publisher started moments ago counts too

    def others() -> list[Publisher]:
        return [p for p in publishers(client) if own is None or not p.runs_in(own)]

    def settled() -> tuple[list[Publisher]] | None:
        found = others()
        return (found,) if all(p.pids for p in found) else None

    done = wait_until(settled, GONE_WAIT_S, interval=0.1)
    return done[0] if done is not None else others()


def one_driver(
    client: Any,
    root: int,
    records: Sequence[Any],
    stop: Callable[[Any], None],
) -> list[str]:
    """Keep process `root`'s node the only lessons' driver of /cmd_vel; return what to say.

    `records` are the lessons' running nodes (NodeRecord: executable, node, tag, label);
    `stop(record)` stops one of them.
    """
    if not _drives(client, root):
        return []
    others = [p for p in publishers(client) if not p.runs_in(root)]
    stopped = []
    for record in records:
        pid = int(record.tag.split(":")[0])
        if pid != root and any(p.runs_in(pid) for p in others):
            stop(record)
            stopped.append(record)
    lines = []
    if stopped:
        names = "; ".join(
            f"{r.node or r.executable} ({r.executable}) that {r.label} had started"
            for r in stopped
        )
        lines.append(f"Stopped {names}: one node at a time drives your lab's robot.")
    stopped_pids = [int(r.tag.split(":")[0]) for r in stopped]
    for publisher in others:
        if not any(publisher.runs_in(pid) for pid in stopped_pids):
            lines.append(
                f"{describe(publisher)} also publishes on /cmd_vel; no lesson started it, so "
                "it keeps running: stop it (Ctrl-C in its terminal) to drive with this "
                "lesson's node alone."
            )
    return lines
