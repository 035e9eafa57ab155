"""Describe the MuJoCo robot as URDF text for /robot_description (read from the model)."""

from __future__ import annotations

import math
from xml.sax.saxutils import quoteattr

import mujoco
import numpy as np

from ..world.frames import FrameJoint, robot_frames

__all__ = ["robot_urdf"]


def _rpy(quat: np.ndarray) -> tuple[float, float, float]:
    w, x, y, z = (float(v) for v in quat)
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


def _origin(pos: np.ndarray, quat: np.ndarray) -> str:
    xyz = " ".join(f"{float(v):.4g}" for v in pos)
    rpy = " ".join(f"{v:.4g}" for v in _rpy(quat))
    return f'<origin xyz="{xyz}" rpy="{rpy}"/>'


def _shape(model: mujoco.MjModel, geom: int) -> str | None:
    size = model.geom_size[geom]
    kind = int(model.geom_type[geom])
    if kind == mujoco.mjtGeom.mjGEOM_BOX:
        return '<box size="{:.4g} {:.4g} {:.4g}"/>'.format(*(2 * size))
    if kind == mujoco.mjtGeom.mjGEOM_CYLINDER:
        return f'<cylinder radius="{size[0]:.4g}" length="{2 * size[1]:.4g}"/>'
    if kind == mujoco.mjtGeom.mjGEOM_SPHERE:
        return f'<sphere radius="{size[0]:.4g}"/>'
    return None


def _link(model: mujoco.MjModel, body: int, name: str) -> list[str]:
    lines = [f"  <link name={quoteattr(name)}>"]
    for geom in range(model.ngeom):
        shape = _shape(model, geom) if model.geom_bodyid[geom] == body else None
        if shape:
            origin = _origin(model.geom_pos[geom], model.geom_quat[geom])
            lines.append(f"    <visual>{origin}<geometry>{shape}</geometry></visual>")
    lines.append("  </link>")
    return lines


def _joint(joint: FrameJoint) -> str:
    kind = "fixed" if joint.fixed else "continuous"
    axis = "" if joint.axis is None else '<axis xyz="{:g} {:g} {:g}"/>'.format(*joint.axis)
    origin = _origin(np.array(joint.origin.xyz), np.array(joint.origin.quat))
    return (
        f"  <joint name={quoteattr(joint.name)} type={quoteattr(kind)}>"
        f"<parent link={quoteattr(joint.parent)}/><child link={quoteattr(joint.child)}/>"
        f"{origin}{axis}</joint>"
    )


def robot_urdf(model: mujoco.MjModel, name: str = "turtlebot3_waffle_pi") -> str:
    """Return a URDF with the robot's links, joints, sensor frames and visual shapes."""
    frames = robot_frames(model)
    lines = ['<?xml version="1.0"?>', f"<robot name={quoteattr(name)}>"]
    lines.append(f"  <link name={quoteattr(frames[0].parent)}/>")
    for joint in frames:
        body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, joint.child)
        if body >= 0:
            lines += _link(model, body, joint.child)
        else:
            lines.append(f"  <link name={quoteattr(joint.child)}/>")
        lines.append(_joint(joint))
    lines.append("</robot>")
    return "\n".join(lines) + "\n"
