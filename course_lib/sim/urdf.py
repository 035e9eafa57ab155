"""Describe the MuJoCo robot as URDF text for /robot_description (read from the model)."""

from __future__ import annotations

import math
from xml.sax.saxutils import quoteattr

import mujoco
import numpy as np

from .model import BASE_BODY, BASE_HEIGHT_M

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


def robot_urdf(model: mujoco.MjModel, name: str = "turtlebot3_waffle_pi") -> str:
    """Return a URDF with the robot's links, joints, sensor frames and visual shapes."""
    base = model.body(BASE_BODY).id
    lines = [
        '<?xml version="1.0"?>',
        f"<robot name={quoteattr(name)}>",
        '  <link name="base_footprint"/>',
    ]
    lines += _link(model, base, "base_link")
    lines.append(
        '  <joint name="base_joint" type="fixed"><parent link="base_footprint"/>'
        f'<child link="base_link"/><origin xyz="0 0 {BASE_HEIGHT_M}"/></joint>'
    )
    for body in range(model.nbody):
        if model.body_parentid[body] != base or body == base:
            continue
        child = model.body(body).name
        joint = model.body_jntadr[body]
        kind = "continuous" if joint >= 0 else "fixed"
        jname = model.joint(joint).name if joint >= 0 else f"{child}_joint"
        axis = " ".join(f"{float(v):g}" for v in model.jnt_axis[joint]) if joint >= 0 else "0 0 1"
        lines += _link(model, body, child)
        lines.append(
            f"  <joint name={quoteattr(jname)} type={quoteattr(kind)}>"
            f'<parent link="base_link"/><child link={quoteattr(child)}/>'
            f"{_origin(model.body_pos[body], model.body_quat[body])}"
            f'<axis xyz="{axis}"/></joint>'
        )
    for site in ("base_scan", "imu_link"):
        sid = model.site(site).id
        lines.append(f'  <link name="{site}"/>')
        lines.append(
            f'  <joint name="{site}_joint" type="fixed"><parent link="base_link"/>'
            f'<child link="{site}"/>{_origin(model.site_pos[sid], model.site_quat[sid])}'
            "</joint>"
        )
    lines.append("</robot>")
    return "\n".join(lines) + "\n"
