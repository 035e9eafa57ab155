"""`make doctor` and `make stop`: what is installed, what runs, and stopping it all."""

from __future__ import annotations

import contextlib
import os
import platform
from importlib import metadata
from pathlib import Path

from . import ament
from .processes import OWNER_ENV, process_environ
from .stopping import StopReport, stop_course

__all__ = ["course_processes", "report", "stop_all"]

_DISTRIBUTIONS = (
    "ros-jazzy-rclpy",
    "ros-jazzy-rmw-fastrtps-cpp",
    "mujoco",
    "meshcat",
    "jupyterlab",
)


def _ancestors() -> set[int]:
    pids, pid = set(), os.getpid()
    while pid > 1:
        pids.add(pid)
        try:
            pid = int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            break
    return pids


def course_processes() -> list[tuple[int, str]]:
    """Return (pid, command line) of every process started by the course, but this one's line."""
    mine = _ancestors()
    found = []
    for entry in Path("/proc").iterdir():
        if (
            entry.name.isdigit()
            and int(entry.name) not in mine
            and OWNER_ENV in process_environ(int(entry.name))
        ):
            with contextlib.suppress(OSError):
                cmd = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode().strip()
                found.append((int(entry.name), cmd))
    return sorted(found)


def stop_all() -> StopReport:
    """Stop this user's course processes: SIGINT, SIGTERM, SIGKILL (see stopping.py)."""
    return stop_course()


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "missing (run `make setup`)"


def report() -> str:
    """Return a short text of the machine, the installed stack and the running processes."""
    lines = [f"Python {platform.python_version()} on {platform.system()} {platform.machine()}"]
    lines += [f"{dist}: {_version(dist)}" for dist in _DISTRIBUTIONS]
    packages = ament.list_packages(ament.workspace_env({}))
    lines.append(f"workspace packages: {', '.join(sorted(packages)) or 'none (run `make setup`)'}")
    lines.append(f"ROS_DOMAIN_ID: {os.environ.get('ROS_DOMAIN_ID', 'not set')}")
    running = course_processes()
    lines.append(f"course processes running: {len(running)}")
    lines += [f"  {pid} {cmd[:100]}" for pid, cmd in running]
    return "\n".join(lines)
