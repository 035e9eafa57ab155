"""The robot model's names and sizes that code outside the simulation reads (no MuJoCo import:
a kernel that records a run or draws a replay's plot never loads the physics engine)."""

from __future__ import annotations

__all__ = ["BASE_BODY", "BASE_HEIGHT_M", "SCAN_SITE", "WHEEL_ACTUATORS", "WHEEL_JOINTS"]

BASE_BODY = "base_link"
BASE_HEIGHT_M = 0.010  # base_link above base_footprint (the ground point), as in the URDF
SCAN_SITE = "base_scan"
WHEEL_JOINTS = ("wheel_left_joint", "wheel_right_joint")
WHEEL_ACTUATORS = ("wheel_left_velocity", "wheel_right_velocity")
