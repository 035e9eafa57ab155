"""`make doctor` and `make stop`: what is installed, what runs, and stopping it all."""

from __future__ import annotations

import contextlib
import os
import platform
import shutil
import signal
import subprocess
from importlib import metadata
from pathlib import Path

from . import ament
from .paths import REPO_ROOT
from .processes import OWNER_ENV, process_environ

__all__ = ["course_processes", "report", "stale_steps", "stop_all"]

# The Makefile's set-up steps: its target, and what `make setup` would do when it is stale.
_SETUP_STEPS = (
    (".venv/.installed", "environment (.venv)", "reinstalls the Python packages"),
    ("rosject/install/.built", "ROS workspace (rosject/install)", "rebuilds it with colcon"),
)

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


def stop_all() -> list[int]:
    """Kill every course process of this user (not this command's own ancestors)."""
    stopped = []
    for pid, _cmd in course_processes():
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(pid, signal.SIGKILL)
            stopped.append(pid)
    return stopped


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "missing (run `make setup`)"


def stale_steps(repo: Path = REPO_ROOT) -> list[str]:
    """Return one line per set-up step: up to date, or stale (asks `make -q`, changes nothing)."""
    if shutil.which("make") is None or not (repo / "Makefile").exists():
        return ["set-up steps: unknown (no make or no Makefile here)"]
    lines = []
    for target, what, redo in _SETUP_STEPS:
        result = subprocess.run(
            ["make", "-q", target], cwd=repo, capture_output=True, check=False, timeout=60
        )
        state = "up to date" if result.returncode == 0 else f"stale: `make setup` {redo}"
        lines.append(f"{what}: {state}")
    return lines


def report() -> str:
    """Return a short text of the machine, the installed stack and the running processes."""
    lines = [f"Python {platform.python_version()} on {platform.system()} {platform.machine()}"]
    lines += [f"{dist}: {_version(dist)}" for dist in _DISTRIBUTIONS]
    packages = ament.list_packages(ament.workspace_env({}))
    lines.append(f"workspace packages: {', '.join(sorted(packages)) or 'none (run `make setup`)'}")
    lines += stale_steps()
    lines.append(f"ROS_DOMAIN_ID: {os.environ.get('ROS_DOMAIN_ID', 'not set')}")
    running = course_processes()
    lines.append(f"course processes running: {len(running)}")
    lines += [f"  {pid} {cmd[:100]}" for pid, cmd in running]
    return "\n".join(lines)
