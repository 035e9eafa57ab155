"""Record a running world's motion from /odom and /joint_states, for an offline replay.

Lesson 7 records the robot driving at the `velocity` it set, then saves the replay so the
motion can be watched later without a kernel.
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import mujoco

from ...viz.replay import ReplayFrame, write_replay
from ..world.model import BASE_HEIGHT_M, WHEEL_JOINTS
from .run_log import wheel_angles

__all__ = ["Recorder", "plan_frames"]


class Recorder:
    """Collect replay frames from the session's subscriptions until stop()."""

    def __init__(self, session: Any, model: mujoco.MjModel, *, fps: int = 30) -> None:
        from nav_msgs.msg import Odometry
        from sensor_msgs.msg import JointState

        self.session = session
        self.model = model
        self.fps = fps
        self.frames: list[ReplayFrame] = []
        self._wheels = [0.0, 0.0]
        self._wheel_adr = [model.joint(j).qposadr[0] for j in WHEEL_JOINTS]
        self._lock = threading.Lock()
        self._last_time = -1.0
        node = session.node
        self._subs = [
            node.create_subscription(Odometry, "/odom", self._on_odom, 50),
            node.create_subscription(JointState, "/joint_states", self._on_joints, 50),
        ]

    def _on_joints(self, msg: Any) -> None:
        with self._lock:
            self._wheels = list(wheel_angles(msg))

    def _on_odom(self, msg: Any) -> None:
        stamp = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        if stamp < self._last_time + 1.0 / self.fps - 1e-9:
            return
        p, o = msg.pose.pose.position, msg.pose.pose.orientation
        qpos = list(self.model.qpos0)
        qpos[0:7] = [p.x, p.y, p.z + BASE_HEIGHT_M, o.w, o.x, o.y, o.z]
        with self._lock:
            for adr, angle in zip(self._wheel_adr, self._wheels, strict=True):
                qpos[adr] = angle
            self.frames.append(ReplayFrame(stamp, tuple(qpos)))
        self._last_time = stamp

    def stop(self) -> list[ReplayFrame]:
        """Stop recording and return the frames."""
        for sub in self._subs:
            self.session.node.destroy_subscription(sub)
        self._subs = []
        return list(self.frames)

    def save(self, path: str | Path) -> Path:
        """Stop recording and write the replay page to `path`."""
        return write_replay(path, self.model, self.stop(), fps=self.fps)


def plan_frames(
    sim: Any, plan: Sequence[tuple[float, float, float]], *, fps: int = 30
) -> list[ReplayFrame]:
    """Drive an in-process Simulation through (linear, angular, seconds) legs; deterministic."""
    frames = [ReplayFrame(sim.time, tuple(sim.data.qpos))]
    for linear, angular, seconds in plan:
        sim.command(linear, angular)
        for _ in range(round(seconds * fps)):
            sim.run_for(1.0 / fps)
            frames.append(ReplayFrame(sim.time, tuple(sim.data.qpos)))
    return frames
