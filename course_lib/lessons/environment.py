"""Lesson 1: what is installed (ROS 2 distro, rclpy, MuJoCo, meshcat) as a small table."""

from __future__ import annotations

from .catalogue.l01_setup_check import versions
from .files import Text

__all__ = ["environment_report", "versions"]


def environment_report() -> Text:
    """Return the versions as an aligned two-column table."""
    rows = versions()
    width = max(map(len, rows))
    return Text("\n".join(f"{k:<{width}}  {v}" for k, v in rows.items()))
