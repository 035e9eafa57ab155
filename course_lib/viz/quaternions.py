"""The one conversion the 3D view needs: a position and a quaternion to a 4x4 transform."""

from __future__ import annotations

from collections.abc import Sequence

import mujoco
import numpy as np

__all__ = ["pose_matrix"]


def pose_matrix(position: Sequence[float], quat: Sequence[float]) -> np.ndarray:
    """Return the 4x4 transform of `position` and unit quaternion `quat` (MuJoCo's w, x, y, z)."""
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, np.asarray(quat, dtype=float))
    matrix = np.eye(4)
    matrix[:3, :3] = rotation.reshape(3, 3)
    matrix[:3, 3] = position
    return matrix
