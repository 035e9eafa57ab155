"""Where a running `make lab` is found: its marker file, the lab a process belongs to.

Low in the stack on purpose: the `ros2` command and its daemon ask it which lab they belong
to without importing the lab itself.
"""

from __future__ import annotations

from pathlib import Path

from ..core.host import procfs
from ..core.paths import runtime_dir

__all__ = [
    "lab_clone_marker",
    "lab_marker",
    "lab_start_marker",
    "owning_lab",
    "recorded_start",
    "running_lab_domain",
]


def lab_marker(pid: int) -> Path:
    """Return the file a running lab (process `pid`) keeps its domain in."""
    return runtime_dir() / f"lab-{pid}.domain"


def lab_clone_marker(pid: int) -> Path:
    """Return the file naming the clone (its folder) lab `pid` runs from.

    The runtime folder is per Unix user, shared by all their clones: a lab's leftovers are
    cleaned up by any clone, but spoken of only by its own.
    """
    return runtime_dir() / f"lab-{pid}.clone"


def lab_start_marker(pid: int) -> Path:
    """Return the file holding lab `pid`'s start time: a later process that reuses the pid
    (even another course process of the user) is never taken for the lab, nor signalled."""
    return runtime_dir() / f"lab-{pid}.start"


def recorded_start(pid: int) -> str | None:
    """Return the start time lab `pid` recorded, or None (a lab of an older course)."""
    try:
        return lab_start_marker(pid).read_text().strip() or None
    except OSError:
        return None


def owning_lab(pid: int) -> int | None:
    """Return the pid of the running lab that process `pid` descends from, if any.

    A JupyterLab terminal's shell, a kernel and the commands they run all descend from the
    `make lab` process, whose marker file names its pid.
    """
    while pid > 1:
        if lab_marker(pid).exists():
            return pid
        pid = procfs.parent_pid(pid)
    return None


def running_lab_domain() -> str | None:
    """Return the ROS domain of this user's newest running `make lab`, if any."""
    markers = sorted(runtime_dir().glob("lab-*.domain"), key=lambda p: p.stat().st_mtime)
    for marker in reversed(markers):
        pid = marker.stem.removeprefix("lab-")
        if pid.isdigit() and procfs.pid_alive(int(pid)):
            return marker.read_text().strip() or None
        marker.unlink(missing_ok=True)  # a lab that was killed
    return None
