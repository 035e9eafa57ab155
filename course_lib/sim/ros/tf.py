"""Fill /tf and /tf_static (tf2_msgs/msg/TFMessage) from the robot's frames and MuJoCo state.

`tf2_msgs` has no wheel: `make setup` builds it in rosject/ (the course's workspace) from the
ROS 2 build wheels; `use_workspace_interfaces()` finds it as a sourced workspace would.
"""

from __future__ import annotations

from geometry_msgs.msg import TransformStamped

from ...core.ament import use_workspace_interfaces
from ...core.errors import CourseError
from ..world.frames import BASE_FRAME, ODOM_FRAME, FrameJoint, Transform, joint_transform
from ..world.model import WHEEL_JOINTS
from ..world.physics import Simulation

use_workspace_interfaces()
try:
    from tf2_msgs.msg import TFMessage
except ImportError as error:  # pragma: no cover - only on a workspace that was never built
    raise CourseError(
        f"tf2_msgs (the message of /tf) cannot be imported: {error}",
        hint="build the course's workspace: make setup",
    ) from error

__all__ = ["TFMessage", "TfFactory"]


def _stamped(parent: str, child: str) -> TransformStamped:
    msg = TransformStamped()
    msg.header.frame_id = parent
    msg.child_frame_id = child
    return msg


def _fill(msg: TransformStamped, transform: Transform) -> None:
    t, r = msg.transform.translation, msg.transform.rotation
    t.x, t.y, t.z = transform.xyz
    r.w, r.x, r.y, r.z = transform.quat


class TfFactory:
    """Reuse one TFMessage per stream: fixed frames, odom -> base_footprint, wheels."""

    def __init__(
        self,
        sim: Simulation,
        frames: list[FrameJoint],
        *,
        odom_frame: str = ODOM_FRAME,
        base_frame: str = BASE_FRAME,
    ) -> None:
        self.sim = sim
        fixed = [j for j in frames if j.fixed]
        by_name = {j.name: j for j in frames}
        self._wheels = [by_name[name] for name in WHEEL_JOINTS]
        self._static = TFMessage(transforms=[_stamped(j.parent, j.child) for j in fixed])
        for msg, joint in zip(self._static.transforms, fixed, strict=True):
            _fill(msg, joint.origin)
        self._odom = TFMessage(transforms=[_stamped(odom_frame, base_frame)])
        self._wheel_msg = TFMessage(transforms=[_stamped(j.parent, j.child) for j in self._wheels])

    def static(self, stamp: object) -> TFMessage:
        """Return /tf_static: every fixed frame of the robot."""
        for msg in self._static.transforms:
            msg.header.stamp = stamp
        return self._static

    def odom(self, stamp: object) -> TFMessage:
        """Return odom -> base_footprint: the pose /odom carries (ground truth, z = 0)."""
        position, quat = self.sim.base_pose3d()
        msg = self._odom.transforms[0]
        msg.header.stamp = stamp
        xyz = (float(position[0]), float(position[1]), 0.0)
        _fill(
            msg, Transform(xyz, (float(quat[0]), float(quat[1]), float(quat[2]), float(quat[3])))
        )
        return self._odom

    def wheels(self, stamp: object) -> TFMessage:
        """Return base_link -> wheel_{left,right}_link at the wheels' current angles."""
        angles, _speeds = self.sim.wheels()
        for msg, joint, angle in zip(
            self._wheel_msg.transforms, self._wheels, angles, strict=True
        ):
            msg.header.stamp = stamp
            _fill(msg, joint_transform(joint, angle))
        return self._wheel_msg
