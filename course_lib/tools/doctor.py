"""`make doctor`: what is installed, what is stale and what runs (it changes nothing)."""

from __future__ import annotations

import os
import platform
import shutil
import subprocess
from importlib import metadata
from pathlib import Path

from ..core import ament
from ..core.paths import REPO_ROOT
from ..processes.ownership import course_processes

__all__ = ["report", "stale_steps"]

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
    running = course_processes()  # the same rule `make stop` uses
    lines.append(f"course processes running: {len(running)}")
    lines += [f"  {p.pid} {p.name}: {' '.join(p.info.argv)[:90]}" for p in running]
    return "\n".join(lines)
