"""Tag the children the course starts with their owner; reap those whose owner is gone.

Each child `children.spawn` starts carries ``COURSE_OWNER=<pid>:<start time>`` in its
environment (with ``COURSE_OWNER_NS``, the PID namespace that pid belongs to), which lets a
later session find and kill what a crashed one left behind, ``COURSE_PROCESS=<name>``, which
`make stop` prints (see ownership.py for the rule), and ``COURSE_SPAWNED``, the command it
ran: a program that merely inherited the tags (a learner's, started from a lab terminal) is
never reaped.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import signal
import time
from collections.abc import Mapping, Sequence

from ..core.host import procfs
from ..core.host.signalling import send

__all__ = [
    "CLONE_ENV",
    "NAME_ENV",
    "OWNER_ENV",
    "OWNER_NS_ENV",
    "SPAWNED_ENV",
    "command_tag",
    "descended_from",
    "holds_dds_socket",
    "owner_alive",
    "owner_tag",
    "reap_orphans",
    "runs_as_spawned",
    "started_by_course",
    "tag_names",
]

OWNER_ENV = "COURSE_OWNER"
OWNER_NS_ENV = "COURSE_OWNER_NS"  # the PID namespace in which COURSE_OWNER's pid is meant
NAME_ENV = "COURSE_PROCESS"
# The clone (its folder) whose course started the process: `make stop` stops its own clone's.
CLONE_ENV = "COURSE_CLONE"
# What `spawn` ran, as a digest of its command line: a process that merely inherited the tags
# (a learner's program started from a lab terminal) runs another command.
SPAWNED_ENV = "COURSE_SPAWNED"


def owner_tag(pid: int | None = None) -> str:
    """Return the tag that marks children of process `pid` (default: this process)."""
    pid = os.getpid() if pid is None else pid
    return f"{pid}:{procfs.start_time(pid)}"


def _other_namespace(namespace: str) -> bool:
    return namespace not in ("", procfs.pid_namespace())


def tag_names(tag: str, pid: int, start: str | None, namespace: str = "") -> bool:
    """Return True if owner tag `tag` (set in PID namespace `namespace`) names `pid`."""
    owner, _, started = tag.partition(":")
    return (
        not _other_namespace(namespace)
        and owner == str(pid)
        and start is not None
        and started == start
    )


def owner_alive(tag: str, namespace: str = "") -> bool:
    """Return True unless the process that owner tag `tag` names is gone.

    A tag set in another PID namespace (a container, `unshare --pid`; see OWNER_NS_ENV)
    cannot be judged from here: it counts as alive, so nothing of another namespace's
    sessions is ever reaped from outside.
    """
    if _other_namespace(namespace):
        return True
    owner = tag.partition(":")[0]
    return owner.isdigit() and tag_names(tag, int(owner), procfs.start_time(int(owner)))


def _command_digest(words: Sequence[str]) -> str:
    # the program by its name: a script's interpreter shows its path, a PATH lookup none
    named = [os.path.basename(words[0]), *words[1:]]
    return hashlib.sha1("\0".join(named).encode(errors="replace")).hexdigest()[:16]


def command_tag(argv: Sequence[str]) -> str:
    """Return the SPAWNED_ENV value for a process started with `argv`."""
    return f"{_command_digest(argv)}:{len(argv)}"


def runs_as_spawned(cmdline: Sequence[str], tag: str) -> bool:
    """Return True if `cmdline` (from /proc) is the command that `tag` records.

    A script run through its `#!` interpreter shows the interpreter first: the recorded
    words are the command line's last ones.
    """
    digest, _, count = tag.partition(":")
    if not count.isdigit() or not 0 < int(count) <= len(cmdline):
        return False
    return _command_digest(cmdline[len(cmdline) - int(count) :]) == digest


def _socket_inodes(pid: int) -> set[str]:
    return {t[8:-1] for t in procfs.fd_targets(pid) if t.startswith("socket:[")}


def holds_dds_socket(pid: int, domain: str) -> bool:
    """Return True if process `pid` has a UDP socket in `domain`'s DDS ports: a ROS process
    (a participant) of that domain, whoever started it."""
    from .domain import port_block  # domain.py needs only the standard library

    if not domain.strip().isdigit():
        return False
    block, inodes = port_block(int(domain)), _socket_inodes(pid)
    for table in ("udp", "udp6"):
        with contextlib.suppress(OSError):
            for line in (procfs.PROC / str(pid) / "net" / table).read_text().splitlines()[1:]:
                fields = line.split()
                if int(fields[1].rsplit(":", 1)[1], 16) in block and fields[9] in inodes:
                    return True
    return False


def started_by_course(pid: int, env: Mapping[str, str], cmdline: Sequence[str]) -> bool:
    """Return True if process `pid` is one the course started, or a ROS process of the
    domain it runs in; False for a program that only inherited the course's environment
    (an editor, a script the learner started from a lab terminal)."""
    return runs_as_spawned(cmdline, env.get(SPAWNED_ENV, "")) or holds_dds_socket(
        pid, env.get("ROS_DOMAIN_ID", "")
    )


def _orphans() -> dict[int, tuple[str, int]]:
    """Return this user's course processes whose owner tag names a process that is gone.

    Each with its start time, so that a pid reused since is never taken for it, and the pid
    its tag names. A program that only inherited the tag (see `started_by_course`) is the
    learner's: never one.
    """
    me, uid = os.getpid(), os.getuid()
    found = {}
    for pid in procfs.pids():
        if pid != me and procfs.owner_uid(pid) == uid:
            started = procfs.start_time(pid)
            env = procfs.environ(pid)
            tag = env.get(OWNER_ENV)
            if (
                started
                and tag
                and not owner_alive(tag, env.get(OWNER_NS_ENV, ""))
                and started_by_course(pid, env, procfs.cmdline(pid) or ())
            ):
                owner = tag.partition(":")[0]
                found[pid] = (started, int(owner) if owner.isdigit() else -1)  # -1: a bad tag
    return found


def reap_orphans(*, rounds: int = 4) -> dict[int, int]:
    """Kill this user's course processes whose owner is gone (then theirs); return each
    one's pid and the pid of the owner it had.

    Only processes whose owner tag names a dead process: never one whose owner still runs
    (JupyterLab's terminals and the learner's programs in them name the live lab).
    """
    killed: dict[int, int] = {}
    for _ in range(rounds):
        batch = _orphans()
        for pid, (started, _owner) in batch.items():
            if procfs.start_time(pid) != started:
                continue  # gone since, and its pid perhaps another process's now
            with contextlib.suppress(ProcessLookupError, PermissionError):
                send(pid, signal.SIGKILL, reason="a leftover: its owner is gone")
        if not batch:
            break
        killed.update({pid: owner for pid, (_started, owner) in batch.items()})
        time.sleep(0.02)  # let the kernel mark them dead before judging their children
    return killed


def descended_from(owners: set[int], reaped: Mapping[int, int]) -> list[int]:
    """Return the `reaped` processes (pid to owner pid) whose owners lead back to `owners`
    (pure)."""
    found: set[int] = set()
    while True:
        more = {pid for pid, owner in reaped.items() if owner in owners | found} - found
        if not more:
            return sorted(found)
        found |= more
