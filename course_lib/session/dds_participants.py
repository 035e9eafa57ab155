"""The DDS participants of a domain on this host: who they are (GUID prefixes, the pid they
carry) and how many there are (the metatraffic ports /proc lists).

Every participant of a domain binds its own metatraffic port, `7410 + 250 * domain + 2 * i`
(Fast DDS's well-known ports), which /proc/net/udp lists for any user. A Fast DDS GUID prefix
carries the low 16 bits of its process's pid (bytes 4-5). The rules are pure; reading /proc
goes through core.host.procfs.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Sequence
from typing import Any

from ..core.host import procfs

__all__ = [
    "bound_participants",
    "dead_participants",
    "endpoint_holders",
    "participant_prefix",
    "prefix_pid",
    "prefix_runs",
    "present_participants",
    "read_bound_participants",
    "running_participants",
    "unseen_participants",
]


def participant_prefix(endpoint_gid: Sequence[int]) -> tuple[int, ...]:
    """Return the participant part (GUID prefix) of a DDS endpoint's GID."""
    return tuple(endpoint_gid[:12])


def endpoint_holders(endpoints: Iterable[Any]) -> dict[str, set[tuple[int, ...]]]:
    """Return the participants (GUID prefixes) holding endpoints of each node, by full name,
    from rclpy `TopicEndpointInfo`s."""
    holders: dict[str, set[tuple[int, ...]]] = {}
    for info in endpoints:
        full = info.node_namespace.rstrip("/") + "/" + info.node_name
        holders.setdefault(full, set()).add(participant_prefix(info.endpoint_gid))
    return holders


def prefix_pid(prefix: Sequence[int]) -> int:
    """Return the (low 16 bits of the) pid a Fast DDS GUID prefix names: bytes 4-5."""
    return prefix[4] | prefix[5] << 8


def prefix_runs(
    prefix: Sequence[int],
    pid_limit: int,
    running: Callable[[int], bool] = procfs.pid_alive,
) -> bool:
    """Return whether a running process may be the participant's: one of the pids below
    `pid_limit` whose low 16 bits the prefix names runs (as `running_participants` decides,
    without listing every process)."""
    return any(running(pid) for pid in range(prefix_pid(prefix), pid_limit, 1 << 16))


def present_participants(
    seen: Iterable[Sequence[int]],
    live_pids: Iterable[int],
    running: Callable[[int], bool] = procfs.pid_alive,
) -> int:
    """Count the seen participants (GUID prefixes) whose process still runs.

    A participant that has left stays seen until its removal arrives (until its lease ends,
    if it was killed): counted, it would stand in for one bound on this host but not seen
    yet. Four first calls at once: one that had ended stood in for the tutorial node, and
    `ros2 topic list -t --no-daemon` listed only its own topics. A killed process that its
    parent has not reaped yet is listed still, but its ports are free: `running` (asked only
    of the pids a seen participant may name) counts it as gone.
    """
    return len(running_participants(seen, live_pids, running))


def running_participants(
    seen: Iterable[Sequence[int]],
    live_pids: Iterable[int],
    running: Callable[[int], bool] = procfs.pid_alive,
) -> set[tuple[int, ...]]:
    """Return the seen participants (GUID prefixes) whose pid (its low 16 bits) is a running
    process of `live_pids` (`running` is asked only of the pids a prefix may name)."""
    by_low_bits: dict[int, list[int]] = {}
    for pid in live_pids:
        by_low_bits.setdefault(pid & 0xFFFF, []).append(pid)
    return {
        tuple(prefix)
        for prefix in seen
        if any(running(pid) for pid in by_low_bits.get(prefix_pid(prefix), ()))
    }


def unseen_participants(
    bound: int,
    seen: Collection[Sequence[int]],
    live_pids: Callable[[], Iterable[int]] = procfs.pids,
    running: Callable[[int], bool] = procfs.pid_alive,
) -> int:
    """Return how many of the `bound` participants on this host are not among `seen` (GUID
    prefixes); the processes are listed only when the count alone says none is missing
    (see `present_participants`)."""
    if len(seen) < bound:
        return bound - len(seen)
    return max(0, bound - present_participants(seen, live_pids(), running))


def bound_participants(domain_id: int, ports: Iterable[int]) -> int:
    """Count the participants of `domain_id` among the UDP ports bound on this host."""
    base = 7400 + 250 * domain_id
    return len({port - base for port in ports if 10 <= port - base < 250 and port % 2 == 0})


def read_bound_participants(domain_id: int) -> int | None:
    """Return how many participants of `domain_id` this host has (None without /proc)."""
    ports = procfs.bound_udp_ports()
    return None if ports is None else bound_participants(domain_id, ports)


def dead_participants(
    seen: Collection[Sequence[int]],
    bound: int | None,
    live_pids: Iterable[int],
    running: Callable[[int], bool] = procfs.pid_alive,
) -> frozenset[tuple[int, ...]]:
    """Return the seen participants (GUID prefixes) whose process has ended.

    A killed process sends no goodbye: the others keep its participant, endpoints and node
    names until its lease ends (20 s, Fast DDS's default). A seen participant whose pid runs
    no more is gone, but only if every participant bound on this host is accounted for by
    a seen one whose pid runs: one whose pid this PID namespace does not show (a container
    sharing the network) is then told apart from one that ended. Without /proc (`bound`
    None), none is known to be dead.
    """
    if bound is None:
        return frozenset()
    prefixes = {tuple(prefix) for prefix in seen}
    alive = running_participants(prefixes, live_pids, running)
    if len(alive) < bound:
        return frozenset()  # a participant bound here is unseen, or its pid is not shown here
    return frozenset(prefixes - alive)
