"""The robot's coordinate frames, read from the MuJoCo model (the one source of the numbers).

/robot_description (the URDF), /tf_static (the fixed frames) and /tf (the wheels) all come from
`robot_frames()`, so editing the MJCF moves every one of them. Frame names follow the
TurtleBot3 Waffle Pi URDF.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from .model import BASE_BODY, BASE_HEIGHT_M

__all__ = [
    "BASE_FRAME",
    "CAMERA_OPTICAL_FRAME",
    "ODOM_FRAME",
    "FrameJoint",
    "Transform",
    "joint_transform",
    "quat_multiply",
    "robot_frames",
]

ODOM_FRAME = "odom"
BASE_FRAME = "base_footprint"
CAMERA_OPTICAL_FRAME = "camera_rgb_optical_frame"
_IDENTITY = (1.0, 0.0, 0.0, 0.0)
# A MuJoCo camera looks along its -z with y up; an optical frame looks along +z with y down.
_MUJOCO_TO_OPTICAL = (0.0, 1.0, 0.0, 0.0)  # half a turn about x, (w, x, y, z)
_SITES = ("base_scan", "imu_link")
_CASTERS = {"caster_left": "caster_back_left_link", "caster_right": "caster_back_right_link"}


@dataclass(frozen=True)
class Transform:
    """A translation (m) and a rotation quaternion (w, x, y, z) of a child frame in its parent."""

    xyz: tuple[float, float, float]
    quat: tuple[float, float, float, float] = _IDENTITY


@dataclass(frozen=True)
class FrameJoint:
    """A URDF joint: `child` at `origin` in `parent`; `axis` set for a wheel (continuous)."""

    name: str
    parent: str
    child: str
    origin: Transform
    axis: tuple[float, float, float] | None = None

    @property
    def fixed(self) -> bool:
        """True for a frame that never moves relative to its parent (/tf_static)."""
        return self.axis is None


def _vec(values: np.ndarray) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in values)
    return (x, y, z)


def _quat(values: np.ndarray | tuple[float, ...]) -> tuple[float, float, float, float]:
    w, x, y, z = (float(v) for v in values)
    return (w, x, y, z)


def quat_multiply(
    a: tuple[float, float, float, float], b: tuple[float, float, float, float]
) -> tuple[float, float, float, float]:
    """Return the Hamilton product a * b of two (w, x, y, z) quaternions."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


def _fixed(
    name: str,
    parent: str,
    child: str,
    xyz: np.ndarray,
    quat: np.ndarray | tuple[float, ...] = _IDENTITY,
) -> FrameJoint:
    return FrameJoint(name, parent, child, Transform(_vec(xyz), _quat(quat)))


def robot_frames(model: mujoco.MjModel) -> list[FrameJoint]:
    """Return every joint of the robot's frame tree, parents before children."""
    base = model.body(BASE_BODY).id
    joints = [_fixed("base_joint", BASE_FRAME, BASE_BODY, np.array([0.0, 0.0, BASE_HEIGHT_M]))]
    for body in range(model.nbody):
        if body == base or model.body_parentid[body] != base:
            continue
        child = model.body(body).name
        origin = Transform(_vec(model.body_pos[body]), _quat(model.body_quat[body]))
        joint = int(model.body_jntadr[body])
        if joint >= 0:
            axis = _vec(model.jnt_axis[joint])
            joints.append(FrameJoint(model.joint(joint).name, BASE_BODY, child, origin, axis))
        else:
            joints.append(FrameJoint(f"{child}_joint", BASE_BODY, child, origin))
    for geom, link in _CASTERS.items():
        joints.append(
            _fixed(link.replace("_link", "_joint"), BASE_BODY, link, model.geom(geom).pos)
        )
    for site in _SITES:
        sid = model.site(site).id
        joints.append(
            _fixed(f"{site}_joint", BASE_BODY, site, model.site_pos[sid], model.site_quat[sid])
        )
    camera = model.camera("camera")
    optical = quat_multiply(_quat(camera.quat), _MUJOCO_TO_OPTICAL)
    joints += [
        _fixed("camera_joint", BASE_BODY, "camera_link", camera.pos),
        _fixed("camera_rgb_joint", "camera_link", "camera_rgb_frame", np.zeros(3)),
        _fixed(
            "camera_rgb_optical_joint",
            "camera_rgb_frame",
            CAMERA_OPTICAL_FRAME,
            np.zeros(3),
            optical,
        ),
    ]
    return joints


def joint_transform(joint: FrameJoint, angle_rad: float) -> Transform:
    """Return a wheel's frame in its parent after turning `angle_rad` about its axis."""
    if joint.axis is None:
        return joint.origin
    half = 0.5 * angle_rad
    ax, ay, az = joint.axis
    norm = math.sqrt(ax * ax + ay * ay + az * az) or 1.0
    s = math.sin(half) / norm
    turn = (math.cos(half), ax * s, ay * s, az * s)
    return Transform(joint.origin.xyz, quat_multiply(joint.origin.quat, turn))
