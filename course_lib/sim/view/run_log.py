"""A lesson's run as data: the robot's poses, wheel angles and speed from /odom and
/joint_states, bounded, model-free (the model is chosen when the replay is written).

Unlike `Recorder` (which a learner starts and stops), a run log listens from the start of a
lesson and keeps only the latest run: when simulated time goes back (the world restarted) or
`restart()` is called (the robot was put back at its start pose), what came before is dropped.
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import mujoco

from ...viz.replay import ReplayFrame
from ..world.model import BASE_HEIGHT_M, WHEEL_JOINTS

__all__ = ["PoseSample", "RunLog", "replay_frames"]


@dataclass(frozen=True)
class PoseSample:
    """The robot at one simulated time: base pose (x y z, quaternion w x y z), wheels, speed."""

    time_s: float
    pose: tuple[float, float, float, float, float, float, float]
    wheels: tuple[float, float]
    speed_mps: float


class RunLog:
    """Log /odom (at most `fps` poses a simulated second, the last `max_s` seconds kept)."""

    def __init__(self, session: Any, *, fps: int = 30, max_s: float = 300.0) -> None:
        from nav_msgs.msg import Odometry
        from sensor_msgs.msg import JointState

        self.session = session
        self.fps = fps
        self.samples: deque[PoseSample] = deque(maxlen=round(fps * max_s))
        self._wheels = (0.0, 0.0)
        self._lock = threading.Lock()
        node = session.node
        self._subs = [
            node.create_subscription(Odometry, "/odom", self._on_odom, 50),
            node.create_subscription(JointState, "/joint_states", self._on_joints, 50),
        ]

    def _on_joints(self, msg: Any) -> None:
        positions = dict(zip(msg.name, msg.position, strict=False))
        wheels = (positions.get(WHEEL_JOINTS[0], 0.0), positions.get(WHEEL_JOINTS[1], 0.0))
        with self._lock:
            self._wheels = wheels

    def _on_odom(self, msg: Any) -> None:
        stamp = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        p, o = msg.pose.pose.position, msg.pose.pose.orientation
        pose = (p.x, p.y, p.z + BASE_HEIGHT_M, o.w, o.x, o.y, o.z)
        with self._lock:
            if self.samples:
                last = self.samples[-1].time_s
                if stamp < last:  # the world restarted: a new run
                    self.samples.clear()
                elif stamp < last + 1.0 / self.fps - 1e-9:
                    return
            self.samples.append(PoseSample(stamp, pose, self._wheels, msg.twist.twist.linear.x))

    @property
    def latest_time_s(self) -> float | None:
        """Return the simulated time of the latest pose, None before the first."""
        with self._lock:
            return self.samples[-1].time_s if self.samples else None

    def restart(self) -> None:
        """Forget the run so far: the next pose starts a new one."""
        with self._lock:
            self.samples.clear()

    def run(self) -> list[PoseSample]:
        """Return the current run's poses, oldest first."""
        with self._lock:
            return list(self.samples)

    def close(self) -> None:
        """Stop listening; idempotent."""
        if not self.session.closed:
            for sub in self._subs:
                self.session.node.destroy_subscription(sub)
        self._subs = []


def replay_frames(model: mujoco.MjModel, run: Sequence[PoseSample]) -> list[ReplayFrame]:
    """Return the replay frames of `run` for `model` (its free joint first, as the world's)."""
    adr = [model.joint(j).qposadr[0] for j in WHEEL_JOINTS]
    frames = []
    for sample in run:
        qpos = list(model.qpos0)
        qpos[0:7] = sample.pose
        for a, angle in zip(adr, sample.wheels, strict=True):
            qpos[a] = angle
        frames.append(ReplayFrame(sample.time_s, tuple(qpos)))
    return frames
