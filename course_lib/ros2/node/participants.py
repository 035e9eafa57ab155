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
from collections.abc import Sequence

from ...core.host import procfs
from ...session.dds_participants import (
    bound_participants,
    endpoint_holders,
    participant_prefix,
    prefix_pid,
    present_participants,
    read_bound_participants,
    unseen_participants,
)

__all__ = [
    "NEWCOMER_S",
    "UNJOINED_S",
    "bound_participants",
    "domain_newcomers",
    "endpoint_holders",
    "of_domain_here",
    "participant_prefix",
    "prefix_pid",
    "present_participants",
    "read_bound_participants",
    "ros2_client_command",
    "starter_command",
    "unseen_participants",
]


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
