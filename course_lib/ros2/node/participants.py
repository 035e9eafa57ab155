"""Who takes part in a ROS domain on this host: its DDS participants, counted from /proc, and
the processes of the domain that may still be starting a node.

Every participant of a domain binds its own metatraffic port, `7410 + 250 * domain + 2 * i`
(Fast DDS's well-known ports), which /proc/net/udp lists for any user; a process that has
not bound one yet but carries the domain's ROS_DOMAIN_ID may be about to (a newcomer). The
rules are pure; reading /proc goes through core.host.procfs. discovery.py decides from these
counts when a client's view of the graph is whole.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Collection, Iterable, Sequence

from ...core.host import procfs

__all__ = [
    "NEWCOMER_S",
    "UNJOINED_S",
    "bound_participants",
    "domain_newcomers",
    "of_domain_here",
    "participant_prefix",
    "prefix_pid",
    "present_participants",
    "read_bound_participants",
    "ros2_client_command",
    "starter_command",
    "unseen_participants",
]


def participant_prefix(endpoint_gid: Sequence[int]) -> tuple[int, ...]:
    """Return the participant part (GUID prefix) of a DDS endpoint's GID."""
    return tuple(endpoint_gid[:12])


def prefix_pid(prefix: Sequence[int]) -> int:
    """Return the (low 16 bits of the) pid a Fast DDS GUID prefix names: bytes 4-5."""
    return prefix[4] | prefix[5] << 8


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
    by_low_bits: dict[int, list[int]] = {}
    for pid in live_pids:
        by_low_bits.setdefault(pid & 0xFFFF, []).append(pid)
    return sum(
        any(running(pid) for pid in by_low_bits.get(prefix_pid(prefix), ())) for prefix in seen
    )


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


# A process of the domain younger than this may still be starting its node (a Python
# importing rclpy before its participant binds: about a second, several on a loaded machine).
NEWCOMER_S = 6.0
# ... but one that has not bound a participant's port by this age, nor loaded ROS (rcl), is
# taken for a process that is no ROS node (a learner's plain script, a kernel not yet at its
# lesson's first cell): it holds no command longer.
UNJOINED_S = 3.0
_RCL_LIBRARY = "librcl.so"
_CLIENT_MODULES = ("course_lib.ros2.command.cli", "course_lib.ros2.command.quick")
# A notebook's `%ros2 launch` runs `python -m course_lib.launch`, which never joins DDS.
_LAUNCH_MODULE = "course_lib.launch"


_STARTER_VERBS = ("launch", "run")


def starter_command(cmdline: Sequence[str]) -> bool:
    """Return whether a command line starts nodes as its children: `ros2 launch` or `ros2
    run` (a terminal's, before and after the quick client hands over to the full one) or a
    notebook's `python -m course_lib.launch`."""
    for i, arg in enumerate(cmdline):
        verb = cmdline[i + 1] if i + 1 < len(cmdline) else ""
        if arg.rpartition("/")[2] == "ros2" and i <= 2:
            return verb in _STARTER_VERBS
        if arg in (*_CLIENT_MODULES, _LAUNCH_MODULE) and i > 0 and cmdline[i - 1] == "-m":
            return arg == _LAUNCH_MODULE or verb in _STARTER_VERBS
    return False


def ros2_client_command(cmdline: Sequence[str]) -> bool:
    """Return whether a command line is a course `ros2` command: no node of its own joins
    from it (`ros2 param get` asks; `ros2 run` and `ros2 launch`, from a terminal or a
    notebook, start their nodes as child processes, which are newcomers themselves)."""
    return any(
        any(module in arg for module in _CLIENT_MODULES)
        or (arg.rpartition("/")[2] == "ros2" and i <= 2)
        or (arg == _LAUNCH_MODULE and i > 0 and cmdline[i - 1] == "-m")
        for i, arg in enumerate(cmdline)
    )


_SHELLS = frozenset({"bash", "sh", "dash", "zsh", "fish", "tmux", "screen"})


def of_domain_here(pid: int, domain_id: int | str, network: str | None) -> bool:
    """Return whether process `pid` carries ROS_DOMAIN_ID `domain_id` in the network
    namespace `network` (procfs.network_namespace()): the same number in another network (a
    walled class hub numbers its learners' domains from 1 too) is another domain."""
    return (
        procfs.environ(pid).get("ROS_DOMAIN_ID", "").strip() == str(domain_id)
        and procfs.network_namespace(pid) == network
    )


def domain_newcomers(
    domain_id: int, *, max_age_s: float = NEWCOMER_S, joined: bool = False
) -> list[int]:
    """Return the pids of this host's processes in `domain_id` started under `max_age_s`
    ago that may be starting a node but have not joined DDS yet (no participant port bound:
    once bound, the participant is counted by read_bound_participants);
    this process, shells and `ros2` query commands left out. With `joined`, those that
    have joined too. Either way, a process with no participant after UNJOINED_S that has not
    loaded ROS is no node starting (a kernel not yet at its lesson, a plain script): it holds
    no command longer.

    What a settled graph cannot show yet: a node whose process has not joined DDS. The
    processes of a domain carry its ROS_DOMAIN_ID (the course starts every one with it);
    one that has joined is counted among the bound participants instead. A process of the
    same number in another network is in another domain (`of_domain_here`).
    """
    try:
        uptime = float(procfs.PROC.joinpath("uptime").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return []
    tick = os.sysconf("SC_CLK_TCK")
    me, found = os.getpid(), []
    network = procfs.network_namespace()
    udp: dict[str, int] | None = None
    for pid in procfs.pids():
        start = procfs.start_time(pid)
        age = None if start is None else uptime - int(start) / tick
        if pid == me or age is None or age > max_age_s:
            continue
        if not of_domain_here(pid, domain_id, network):
            continue
        cmdline = procfs.cmdline(pid) or ()
        if not cmdline or cmdline[0].rpartition("/")[2] in _SHELLS:
            continue
        if starter_command(cmdline):
            # a launch (or run) that has not started its nodes yet is a node starting: a
            # command typed right after `ros2 launch ... &` said "Node not found"; once its
            # nodes are started, they are the newcomers (never longer than max_age_s)
            if not procfs.has_children(pid):
                found.append(pid)
            continue
        if ros2_client_command(cmdline):
            continue
        udp = procfs.udp_socket_inodes() if udp is None else udp
        ports = [udp[t] for t in procfs.fd_targets(pid) if t in udp]
        if bound_participants(domain_id, ports):  # joined: read_bound_participants counts it
            if joined:
                found.append(pid)
        elif age <= UNJOINED_S or procfs.maps_library(pid, _RCL_LIBRARY):
            found.append(pid)  # may still be starting a node (a slow `import rclpy` has rcl)
    return found
