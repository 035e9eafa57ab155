"""A lesson's run as data: the robot's poses, wheel angles and speed from the simulation's
samples of /odom and the wheels (sim.world.samples), bounded, model-free (the model is chosen
when the replay is written).

Unlike `Recorder` (which a learner starts and stops), a session has one run log
(`run_log(session)`), listening from the first lesson that asks until the session closes:
its subscriptions are never destroyed while the session spins (rclpy's executor can trip
over a subscription destroyed from another thread). It keeps the latest run only: when
simulated time goes back (the world restarted), what came before is dropped (`epoch` counts
it); a lesson marks where its own run starts with `mark()` and reads it with `run(since)`.
"""

from __future__ import annotations

import threading
import weakref
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..world.robot import BASE_HEIGHT_M, WHEEL_JOINTS
from ..world.samples import RobotSample
from .samples_feed import SamplesFeed, samples_feed

if TYPE_CHECKING:  # a kernel that records a run never needs MuJoCo or meshcat until it saves
    import mujoco

    from ...viz.replay import ReplayFrame

__all__ = ["PoseLog", "PoseSample", "RunLog", "replay_frames", "run_log", "wheel_angles"]


def wheel_angles(msg: Any) -> tuple[float, float]:
    """Return the left and right wheel angles (rad) of a /joint_states message (0 if absent)."""
    positions = dict(zip(msg.name, msg.position, strict=False))
    left, right = (positions.get(joint, 0.0) for joint in WHEEL_JOINTS)
    return left, right


@dataclass(frozen=True)
class PoseSample:
    """The robot at one simulated time: base pose (x y z, quaternion w x y z), wheels, speed."""

    time_s: float
    pose: tuple[float, float, float, float, float, float, float]
    wheels: tuple[float, float]
    speed_mps: float


class PoseLog:
    """The latest run's poses, at most `fps` a simulated second, the last `max_s` seconds."""

    def __init__(self, *, fps: int = 30, max_s: float = 300.0) -> None:
        self.fps = fps
        self.samples: deque[PoseSample] = deque(maxlen=round(fps * max_s))
        self.epoch = 0  # how many times simulated time went back (the world restarted)
        self._lock = threading.Lock()

    def add(self, sample: PoseSample) -> None:
        """Keep `sample` (a world restart drops the run before it; a pose within 1/fps s of
        the last one is skipped)."""
        with self._lock:
            if self.samples:
                last = self.samples[-1].time_s
                if sample.time_s < last:  # the world restarted: a new run
                    self.samples.clear()
                    self.epoch += 1
                elif sample.time_s < last + 1.0 / self.fps - 1e-9:
                    return
            self.samples.append(sample)

    @property
    def latest_time_s(self) -> float | None:
        """Return the simulated time of the latest pose, None before the first."""
        with self._lock:
            return self.samples[-1].time_s if self.samples else None

    def mark(self) -> tuple[int, float | None]:
        """Return where a run starting now begins (for `run(since=...)`)."""
        with self._lock:
            return self.epoch, (self.samples[-1].time_s if self.samples else None)

    def run(self, since: tuple[int, float | None] | None = None) -> list[PoseSample]:
        """Return the poses of the run that began at `since` (a `mark()`), oldest first.

        After a world restart (a later epoch) every pose kept belongs to the new run.
        """
        with self._lock:
            samples = list(self.samples)
            epoch = self.epoch
        if since is None or since[0] != epoch or since[1] is None:
            return samples
        return [s for s in samples if s.time_s > since[1]]


class RunLog(PoseLog):
    """A PoseLog fed by a session's samples of /odom and the wheels (sim.world.samples)."""

    def __init__(self, session: Any, *, fps: int = 30, max_s: float = 300.0) -> None:
        super().__init__(fps=fps, max_s=max_s)
        self.session = session
        self._feed: SamplesFeed | None = samples_feed(session)
        self._feed.add(self._on_samples)

    def _on_samples(self, samples: list[RobotSample]) -> None:
        for s in samples:
            pose = (s.x, s.y, BASE_HEIGHT_M, s.qw, s.qx, s.qy, s.qz)
            wheels = (s.wheel_left_rad, s.wheel_right_rad)
            self.add(PoseSample(s.time_s, pose, wheels, s.linear_mps))

    def close(self) -> None:
        """Stop listening (the session is closing, or a test is done); idempotent."""
        if self._feed is not None:
            self._feed.remove(self._on_samples)
        self._feed = None


_logs: weakref.WeakKeyDictionary[Any, RunLog] = weakref.WeakKeyDictionary()
_logs_lock = threading.Lock()


def run_log(session: Any, *, fps: int = 30) -> RunLog:
    """Return `session`'s run log, subscribing the first time (at `fps`)."""
    with _logs_lock:
        log = _logs.get(session)
        if log is None:
            log = _logs[session] = RunLog(session, fps=fps)
        return log


def replay_frames(model: mujoco.MjModel, run: Sequence[PoseSample]) -> list[ReplayFrame]:
    """Return the replay frames of `run` for `model` (its free joint first, as the world's)."""
    from ...viz.replay import ReplayFrame

    adr = [model.joint(j).qposadr[0] for j in WHEEL_JOINTS]
    frames = []
    for sample in run:
        qpos = list(model.qpos0)
        qpos[0:7] = sample.pose
        for a, angle in zip(adr, sample.wheels, strict=True):
            qpos[a] = angle
        frames.append(ReplayFrame(sample.time_s, tuple(qpos)))
    return frames
