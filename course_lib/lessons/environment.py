"""Lesson 1: what is installed (ROS 2 distro, rclpy, MuJoCo, meshcat) as a small table."""

from __future__ import annotations

import importlib.metadata as metadata
import os
import platform

from .files import Text

__all__ = ["environment_report", "versions"]

_DISTRIBUTIONS = {
    "rclpy": "ros-jazzy-rclpy",
    "Fast DDS (rmw)": "ros-jazzy-rmw-fastrtps-cpp",
    "MuJoCo": "mujoco",
    "meshcat": "meshcat",
    "JupyterLab": "jupyterlab",
}


def _has(dist: str) -> bool:
    try:
        metadata.version(dist)
    except metadata.PackageNotFoundError:
        return False
    return True


def versions() -> dict[str, str]:
    """Return the versions of what the course runs on ('missing' when not installed)."""
    distro = os.environ.get("ROS_DISTRO") or ("jazzy" if _has("ros-jazzy-rclpy") else "unknown")
    found = {"ROS 2 distro": distro}
    for label, dist in _DISTRIBUTIONS.items():
        try:
            found[label] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            found[label] = "missing"
    found["Python"] = platform.python_version()
    return found


def environment_report() -> Text:
    """Return the versions as an aligned two-column table."""
    rows = versions()
    width = max(map(len, rows))
    return Text("\n".join(f"{k:<{width}}  {v}" for k, v in rows.items()))
