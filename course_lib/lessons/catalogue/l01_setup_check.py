"""Lesson 1, setup check: what is installed, and a session that talks ROS 2 in its own domain."""

from __future__ import annotations

import importlib.metadata as metadata
import os
import platform

from .spec import Check, LessonSpec, LessonView, check

__all__ = ["SPEC", "installed_checks", "versions"]

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


def installed_checks(found: dict[str, str]) -> list[Check]:
    """Return lesson 1's checks of what is installed, from `versions()`."""
    return [
        check("ROS 2 Jazzy's rclpy is installed", found["ROS 2 distro"] == "jazzy"),
        check(
            "MuJoCo and meshcat are installed",
            "missing" not in (found["MuJoCo"], found["meshcat"]),
            "run `make setup` in a terminal, then restart the kernel.",
        ),
    ]


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 1's checks: installed, a live session, the workspace built."""
    from ...core import ament
    from ...core.errors import CourseError

    try:
        exes = ament.package_executables("parameter_tests", lesson.session.env)
    except CourseError:  # the package is not in the workspace at all
        exes = []
    return [
        *installed_checks(versions()),
        check(
            "your session talks ROS 2 in its own domain",
            not lesson.session.closed,
            "run the first cell again.",
        ),
        check(
            "the workspace is built: parameter_tests has param_vel",
            "param_vel" in exes,
            "run `make setup` in a terminal (it builds rosject/ with colcon).",
        ),
    ]


SPEC = LessonSpec(1, "01_setup_check.ipynb", "Setup check", self_check)
