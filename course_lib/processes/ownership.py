"""Which running processes are the course's: the rule behind `make stop`.

A process of this user is the course's when

- `processes.spawn` started it: its ``COURSE_OWNER`` names its parent (pid and start time).
  Kernels' nodes, simulations and viewers, a lab's JupyterLab and daemon, launch's nodes;
- it is a leftover: its ``COURSE_OWNER`` names a process that is gone, and it runs the
  command the course started it with, or it is a ROS process (a DDS socket) of its domain
  (the same rule as `orphans.reap_orphans`);
- it serves a Unix socket in the runtime folder (the ``ros2`` daemons, a lab's service);
- it is a running `make lab`, found by its ``lab-<pid>.*`` marker in the runtime folder.

A process that merely inherited the environment (JupyterLab's kernels and terminals, the
learner's shells and editors in them) names a live owner that is not its parent: it is never
the course's, even with a copied ``COURSE_OWNER``. Once that owner is gone (the lab stopped),
such a program is still the learner's unless it is a ROS process of the lab's domain:
`make stop` leaves it running and names it (`own_programs`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from ..core.host import procfs
from ..core.paths import REPO_ROOT, runtime_dir
from .lab_markers import recorded_start
from .orphans import (
    CLONE_ENV,
    NAME_ENV,
    OWNER_ENV,
    OWNER_NS_ENV,
    owner_alive,
    started_by_course,
    tag_names,
)

__all__ = [
    "LAB_ENV",
    "CourseProcess",
    "ProcessInfo",
    "course_processes",
    "current_lab",
    "is_course_lab",
    "lab_markers",
    "own_programs",
    "protected_pids",
    "read_process",
]

LAB_ENV = "COURSE_LAB"  # set in a lab's JupyterLab, and so in its kernels and terminals


@dataclass(frozen=True)
class ProcessInfo:
    """What /proc says about one process."""

    pid: int
    ppid: int
    pgid: int
    start: str
    uid: int
    argv: tuple[str, ...]
    env: dict[str, str]
    session: int
    tty: int  # the controlling terminal's device number, 0 for none

    @property
    def terminal_shell(self) -> bool:
        """Return whether this process leads a terminal's session (a lab terminal's shell)."""
        return self.session == self.pid and self.tty != 0

    @property
    def owner(self) -> str:
        return self.env.get(OWNER_ENV, "")

    @property
    def owner_namespace(self) -> str:
        return self.env.get(OWNER_NS_ENV, "")

    @property
    def clone(self) -> str:
        """Return the folder of the clone whose course started this process: its tag, or for
        an untagged one the clone its command runs from when that is this one; "" when
        unknown."""
        if self.env.get(CLONE_ENV):
            return self.env[CLONE_ENV]
        here = f"{REPO_ROOT}{os.sep}"
        return str(REPO_ROOT) if any(arg.startswith(here) for arg in self.argv) else ""


@dataclass(frozen=True)
class CourseProcess:
    """One process of the course, with the name `make stop` prints and why it counts."""

    info: ProcessInfo
    name: str
    reason: str

    @property
    def pid(self) -> int:
        return self.info.pid


def read_process(pid: int) -> ProcessInfo | None:
    """Return /proc's view of `pid`, or None if it is gone, a zombie, or unreadable."""
    fields = procfs.stat_fields(pid)
    uid = procfs.owner_uid(pid)
    argv = procfs.cmdline(pid)
    if fields is None or uid is None or argv is None or fields[0] in ("Z", "X"):
        return None
    return ProcessInfo(
        pid=pid,
        ppid=int(fields[1]),
        pgid=int(fields[2]),
        session=int(fields[3]),
        tty=int(fields[4]),
        start=fields[19],
        uid=uid,
        argv=argv,
        env=procfs.environ(pid),
    )


def _user_processes() -> dict[int, ProcessInfo]:
    uid = os.getuid()
    found = {}
    for pid in procfs.pids():
        info = read_process(pid)
        if info is not None and info.uid == uid:
            found[info.pid] = info
    return found


def _ancestors(pid: int, table: dict[int, ProcessInfo]) -> set[int]:
    """Return `pid` and its ancestors (read from /proc when not in `table`)."""
    seen: set[int] = set()
    while pid > 1 and pid not in seen:
        seen.add(pid)
        info = table.get(pid) or read_process(pid)
        if info is None:
            break
        pid = info.ppid
    return seen


def current_lab() -> int | None:
    """Return the pid of the lab this process runs in (a lab's terminal or kernel), if any."""
    tag = os.environ.get(OWNER_ENV, "")
    if os.environ.get(LAB_ENV) == "1" and owner_alive(tag, os.environ.get(OWNER_NS_ENV, "")):
        return int(tag.partition(":")[0])
    return None


def protected_pids(table: dict[int, ProcessInfo]) -> set[int]:
    """Return what `make stop` never stops: itself, its ancestors, and the lab it runs in.

    Inside a lab (``COURSE_LAB=1``, a JupyterLab terminal), the lab named by this process's
    owner tag and its JupyterLab keep running, so the learner's page and terminals stay.
    """
    keep = _ancestors(os.getpid(), table)
    lab = current_lab()
    if lab is not None:
        keep.add(lab)
        keep |= {p.pid for p in table.values() if p.ppid == lab and _is_jupyterlab(p)}
    return keep


def _is_jupyterlab(info: ProcessInfo) -> bool:
    names = [Path(a).name for a in info.argv[:2]]
    return info.env.get(NAME_ENV) == "jupyterlab" or "jupyter-lab" in names


def _socket_holders(table: dict[int, ProcessInfo]) -> set[int]:
    """Return the processes that hold a Unix socket bound in the runtime folder."""
    folder = f"{runtime_dir()}{os.sep}"
    sockets = procfs.unix_socket_paths().items()
    inodes = {inode for inode, path in sockets if path.startswith(folder)}
    return {pid for pid in table if inodes and not inodes.isdisjoint(procfs.fd_targets(pid))}


def lab_markers() -> dict[int, list[Path]]:
    """Return the files in the runtime folder that name a lab (``lab-<pid>.*``), by pid."""
    found: dict[int, list[Path]] = {}
    for marker in runtime_dir().glob("lab-*.*"):
        pid = marker.name.removeprefix("lab-").split(".", 1)[0]
        if pid.isdigit():
            found.setdefault(int(pid), []).append(marker)
    return found


def is_course_lab(pid: int, table: dict[int, ProcessInfo] | None = None) -> bool:
    """Return True if `pid` runs a course lab of this user (a reused pid is none): its owner,
    its command and, where the lab recorded it, its start time."""
    info = read_process(pid) if table is None else table.get(pid)
    if info is None or info.uid != os.getuid() or "course_lib" not in " ".join(info.argv):
        return False
    recorded = recorded_start(pid)
    return recorded is None or recorded == info.start


def _lab_pids(table: dict[int, ProcessInfo]) -> set[int]:
    return {pid for pid in lab_markers() if is_course_lab(pid, table)}


def _reason(info: ProcessInfo, table: dict[int, ProcessInfo], labs: set[int]) -> str:
    owner, namespace = info.owner, info.owner_namespace
    if owner:
        if not owner_alive(owner, namespace):
            return "leftover" if started_by_course(info.pid, info.env, info.argv) else ""
        parent = table.get(info.ppid)
        if parent is not None and tag_names(owner, parent.pid, parent.start, namespace):
            return "child"
    return "lab" if info.pid in labs else ""


def _name(info: ProcessInfo, reason: str) -> str:
    if info.env.get(NAME_ENV):
        return info.env[NAME_ENV]
    if reason == "lab":
        return "lab"
    argv = list(info.argv) or ["?"]
    if "-m" in argv[:-1]:
        return argv[argv.index("-m") + 1]
    return Path(argv[0]).name


def course_processes() -> list[CourseProcess]:
    """Return this user's course processes, but never this one, its ancestors or its lab."""
    table = _user_processes()
    keep = protected_pids(table)
    labs = _lab_pids(table)
    sockets = _socket_holders(table)
    found = []
    for info in table.values():
        if info.pid in keep:
            continue
        reason = _reason(info, table, labs) or ("socket" if info.pid in sockets else "")
        if reason:
            found.append(CourseProcess(info, _name(info, reason), reason))
    return sorted(found, key=lambda p: p.pid)


def own_programs() -> list[CourseProcess]:
    """Return the learner's own programs that outlived their lab: processes of this user that
    inherited a lab's environment (its owner tag names a process that is gone) but are
    neither started by the course nor ROS processes of its domain. `make stop` keeps them."""
    table = _user_processes()
    keep = protected_pids(table)
    found = []
    for info in table.values():
        owner = info.owner
        if info.pid in keep or not owner or owner_alive(owner, info.owner_namespace):
            continue
        if not started_by_course(info.pid, info.env, info.argv):
            found.append(CourseProcess(info, _name(info, ""), "yours"))
    return sorted(found, key=lambda p: p.pid)
