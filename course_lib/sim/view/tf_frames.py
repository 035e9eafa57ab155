"""Draw the robot's TF frames in the 3D view: one red-green-blue triad (x, y, z) per frame.

The triads live under `/meshcat/tf`, nested like the TF tree (odom, then base_footprint, then
base_link and its children), so moving the robot moves one transform and the wheels two, just
as /tf does. The group starts hidden; the viewer page's "TF frames" box shows it.
"""

from __future__ import annotations

from typing import Any

import meshcat.geometry as g
import mujoco
import numpy as np
from meshcat.commands import SetObject, SetProperty, SetTransform
from meshcat.path import Path

from ...viz.quaternions import pose_matrix
from ..world.frames import BASE_FRAME, ODOM_FRAME, FrameJoint, Transform, joint_transform
from ..world.model import BASE_BODY

__all__ = ["TF_ROOT", "TfView"]

TF_ROOT = ("meshcat", "tf")
_ODOM_SCALE_M = 0.25
_FRAME_SCALE_M = 0.08


class TfView:
    """Meshcat commands for the frame tree of `joints` and its moving transforms."""

    def __init__(self, model: mujoco.MjModel, joints: list[FrameJoint]) -> None:
        self.joints = joints
        self.paths = {ODOM_FRAME: Path((*TF_ROOT, ODOM_FRAME))}
        self.paths[BASE_FRAME] = self.paths[ODOM_FRAME].append(BASE_FRAME)
        for joint in joints:
            self.paths[joint.child] = self.paths[joint.parent].append(joint.child)
        self._wheels = [(j, model.joint(j.name).qposadr[0]) for j in joints if not j.fixed]
        self._base_qpos = model.joint(model.body(BASE_BODY).jntadr[0]).qposadr[0]

    def draw_commands(self) -> list[Any]:
        """Return the commands that draw every frame (hidden) and place the fixed ones."""
        commands: list[Any] = []
        for frame, path in self.paths.items():
            scale = _ODOM_SCALE_M if frame == ODOM_FRAME else _FRAME_SCALE_M
            commands.append(SetObject(g.triad(scale), path=path))
        commands += [
            SetTransform(pose_matrix(j.origin.xyz, j.origin.quat), self.paths[j.child])
            for j in self.joints
        ]
        commands.append(SetProperty("visible", False, Path(TF_ROOT)))
        return commands

    def update_commands(self, data: mujoco.MjData) -> list[Any]:
        """Return odom -> base_footprint (the pose /odom reports) and the wheels' rotations."""
        return [SetTransform(matrix, path) for path, matrix in self.update_poses(data)]

    def update_poses(self, data: mujoco.MjData) -> list[tuple[Path, np.ndarray]]:
        """Return the moving frames' paths and 4x4 transforms (what update_commands sends)."""
        at = self._base_qpos
        x, y = float(data.qpos[at]), float(data.qpos[at + 1])
        w, qx, qy, qz = (float(v) for v in data.qpos[at + 3 : at + 7])
        base = Transform((x, y, 0.0), (w, qx, qy, qz))
        poses = [(self.paths[BASE_FRAME], pose_matrix(base.xyz, base.quat))]
        for joint, address in self._wheels:
            moved = joint_transform(joint, float(data.qpos[address]))
            poses.append((self.paths[joint.child], pose_matrix(moved.xyz, moved.quat)))
        return poses
