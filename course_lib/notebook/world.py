"""The notebook's handle on the simulated world (`course_lib.notebook.start_world()` returns one).

Lesson 3 starts the world and looks at it; lesson 7 reads the robot's speed from it. The
simulation, which serves the 3D view, is a child of the course session, so it ends with it.
"""

from __future__ import annotations

import collections
import logging
import math
import os
import threading
import time
from dataclasses import dataclass
from typing import Any, Protocol

from ..config.simulation import SimulationSettings
from ..core.errors import CourseError
from ..processes.children import OutputLine
from ..sim.view.samples_feed import samples_feed
from ..sim.world.kinematics import Pose2D, yaw_from_quat
from ..sim.world.samples import RobotSample

__all__ = ["OdomReading", "World"]

# A reading received longer ago than this is old: a resting robot's samples come every two
# seconds (sim.world.samples), so a reader that needs a recent one asks for it (FRESH_TOPIC), at
# most this often while it waits. A paused world sends none: its latest reading is the answer.
STALE_S = 0.25

_log = logging.getLogger(__name__)
_worlds: dict[int, World] = {}
_worlds_lock = threading.RLock()


@dataclass(frozen=True)
class OdomReading:
    """One /odom sample: simulated time, pose, forward speed (m/s) and yaw rate (rad/s)."""

    time_s: float
    pose: Pose2D
    linear_mps: float
    angular_radps: float


class SimulationProcess(Protocol):
    """What a World uses of its simulation's process: the session's `ChildProcess`, or in a
    lab the lab's (`lab.remote.LabProcess`)."""

    @property
    def pid(self) -> int: ...

    @property
    def alive(self) -> bool: ...

    @property
    def returncode(self) -> int | None: ...

    @property
    def lines(self) -> list[OutputLine]: ...

    def stop(self, *, timeout: float = 5.0) -> int | None: ...


def _reading(sample: RobotSample) -> OdomReading:
    yaw = yaw_from_quat(sample.qw, sample.qx, sample.qy, sample.qz)
    return OdomReading(
        sample.time_s, Pose2D(sample.x, sample.y, yaw), sample.linear_mps, sample.angular_radps
    )


class World:
    """A running simulation (and its 3D view) owned by a course session."""

    def __init__(
        self,
        session: Any,
        settings: SimulationSettings,
        process: SimulationProcess,
        viewer: Any = None,
        *,
        shared: bool = False,
    ) -> None:
        from geometry_msgs.msg import Twist
        from std_msgs.msg import Empty, UInt32

        from ..session.quiet_events import quiet_publisher, quiet_subscription
        from ..sim.ros.topics import FRESH_TOPIC, RESET_DONE_TOPIC, RESET_TOPIC, reset_done_qos

        self.session = session
        self.settings = settings
        self.process = process
        self.viewer = viewer
        self.shared = shared  # the lab's world, which every notebook of the lab shows
        self._latest: OdomReading | None = None
        # the samples, made readings only when read: a resting robot's hundred a message
        # mostly go unread (0.6 ms of the kernel's ROS thread per message, made one by one)
        self._recent: collections.deque[tuple[int, RobotSample]] = collections.deque(maxlen=250)
        self._received = 0  # readings so far: wait_for_odom looks at each new one
        self._received_at = 0.0  # when the latest came (monotonic)
        self._asked_at = -math.inf  # when this handle last asked for fresh samples
        self._cond = threading.Condition()
        self._listeners: list[Any] = []
        node = session.node
        # /odom's samples, a few to a message (sim.world.samples): a tenth of /odom's wake-ups,
        # on the session's one subscription (the speed plot and the replay log read it too)
        self._feed = samples_feed(session)
        self._feed.add(self._on_samples)
        # made on the first drive(): a kernel that only watches never counts as a driver
        self._cmd: Any = None
        self._reset = node.create_publisher(
            UInt32, RESET_TOPIC, 10, event_callbacks=quiet_publisher()
        )
        self._fresh = node.create_publisher(
            Empty, FRESH_TOPIC, 10, event_callbacks=quiet_publisher()
        )
        self._empty = Empty()
        self._reset_sub = node.create_subscription(
            UInt32,
            RESET_DONE_TOPIC,
            self._on_reset_done,
            reset_done_qos(),
            event_callbacks=quiet_subscription(),
        )
        self._resets_done: set[int] = set()
        self._reset_count = 0
        self._twist_type, self._number_type = Twist, UInt32

    def __repr__(self) -> str:
        return f"<World {'running' if self.alive else 'stopped'}>"

    def _on_samples(self, samples: list[RobotSample]) -> None:
        if not samples:
            return
        with self._cond:
            for sample in samples:
                self._received += 1
                self._recent.append((self._received, sample))
            self._latest = _reading(samples[-1])
            self._received_at = time.monotonic()
            self._cond.notify_all()
        listeners = list(self._listeners)
        if not listeners:
            return
        for reading in map(_reading, samples):
            for listener in listeners:
                listener(reading)

    def _on_reset_done(self, msg: Any) -> None:
        with self._cond:
            self._resets_done.add(msg.data)
            self._cond.notify_all()

    @property
    def alive(self) -> bool:
        """Return True while the simulation process runs."""
        return self.process.alive and not self.session.closed

    def _check_alive(self) -> None:
        if not self.alive:
            tail = "\n".join(line.text for line in self.process.lines[-5:])
            raise CourseError(
                f"The simulation is not running (exit code "
                f"{self.process.returncode}).\n{tail}".rstrip(),
                hint="start it again with start_world().",
            )

    def add_odom_listener(self, listener: Any) -> None:
        """Call `listener(OdomReading)` on every /odom sample from now on (an exercise's log)."""
        self._listeners.append(listener)

    def remove_odom_listener(self, listener: Any) -> None:
        """Stop calling a listener given to `add_odom_listener`."""
        self._listeners = [f for f in self._listeners if f is not listener]

    def wait_for_odom(self, predicate: Any = None, timeout: float = 10.0) -> OdomReading:
        """Return the latest /odom reading if it matches `predicate` (or none is given), else
        the first later one that does; raise TimeoutError.

        The predicate runs without the world's lock: the session's ROS thread takes that lock
        for every sample, so a predicate that waits on ROS (a parameter get) must not hold it.
        """
        started = time.monotonic()
        deadline = started + timeout
        with self._cond:
            latest, seen, age = self._latest, self._received, started - self._received_at
        matched = None
        if latest is not None and (predicate is None or predicate(latest)):
            matched = latest  # the answer, unless a newer reading comes when asked
        if matched is not None and age <= STALE_S:
            return matched
        came = 0  # readings that arrived during the wait (the error tells none from no match)
        while True:
            with self._cond:
                fresh = [(n, sample) for n, sample in self._recent if n > seen]
                if not fresh:
                    now = time.monotonic()
                    if matched is not None and now - started > STALE_S:
                        return matched  # no newer one came when asked: a paused world's last
                    remaining = deadline - now
                    if remaining <= 0:
                        raise self._no_match(timeout, came)
                    if now - max(self._received_at, self._asked_at) > STALE_S:
                        self._asked_at = now
                        # a DDS write never waits on the ROS thread that takes this lock
                        self._fresh.publish(self._empty)  # a resting robot's: send them now
                    self._cond.wait(min(remaining, STALE_S / 2))
                    continue
            for number, sample in fresh:
                seen, came = number, came + 1
                reading = _reading(sample)
                if predicate is None or predicate(reading):
                    return reading
            if time.monotonic() >= deadline:
                raise self._no_match(timeout, came)

    def _no_match(self, timeout: float, came: int) -> TimeoutError:
        """Return the error of a wait that found no matching reading among the `came` that
        arrived (a stopped simulation raises its own error here instead)."""
        self._check_alive()
        if came:
            return TimeoutError(
                f"no matching /odom within {timeout:g} s ({came} readings came, none matched)"
            )
        return TimeoutError(
            f"no /odom within {timeout:g} s: the simulation runs but sent no reading"
        )

    def odom(self) -> OdomReading:
        """Return the latest /odom reading."""
        self._check_alive()
        return self.wait_for_odom()

    def pose(self) -> Pose2D:
        """Return the robot's latest pose (x m, y m, yaw rad) from /odom."""
        return self.odom().pose

    def speed(self) -> tuple[float, float]:
        """Return (forward speed m/s, yaw rate rad/s) from the latest /odom."""
        reading = self.odom()
        return reading.linear_mps, reading.angular_radps

    def wait_sim_time(self, seconds: float, timeout: float = 30.0) -> OdomReading:
        """Wait until /odom reports simulated time >= `seconds`."""
        return self.wait_for_odom(lambda r: r.time_s >= seconds - 1e-6, timeout)

    def _wait_for_peer(self, count: Any, problem: str, timeout: float = 5.0) -> None:
        """Wait until `count()` (matched subscribers or publishers) is non-zero."""
        deadline = time.monotonic() + timeout
        while count() == 0:
            self._check_alive()
            if time.monotonic() > deadline:
                raise TimeoutError(problem)
            with self._cond:
                self._cond.wait(0.02)

    def _matched(self, publisher: Any) -> None:
        """Wait until the simulation subscribes to `publisher` (else the first message is lost)."""
        problem = f"the simulation does not listen on {publisher.topic_name}"
        self._wait_for_peer(publisher.get_subscription_count, problem)

    def _matched_subscription(self, subscription: Any) -> None:
        """Wait until the simulation publishes to `subscription`."""
        problem = f"the simulation does not publish {subscription.topic_name}"
        self._wait_for_peer(subscription.get_publisher_count, problem)

    def drive(self, linear_mps: float = 0.0, angular_radps: float = 0.0) -> None:
        """Publish one /cmd_vel twist (the robot keeps it until the next one)."""
        self._check_alive()
        msg = self._twist_type()
        msg.linear.x, msg.angular.z = float(linear_mps), float(angular_radps)
        if self._cmd is None:
            self._cmd = self.session.node.create_publisher(self._twist_type, "/cmd_vel", 10)
        self._matched(self._cmd)
        self._cmd.publish(msg)

    def reset(self, timeout: float = 5.0) -> OdomReading:
        """Put the robot back at its start pose, at rest (simulated time keeps running)."""
        self._check_alive()
        self._reset_count += 1
        number = (os.getpid() % 0x10000) << 16 | (self._reset_count % 0x10000)
        self._matched(self._reset)
        self._matched_subscription(self._reset_sub)
        self._reset.publish(self._number_type(data=number))
        deadline = time.monotonic() + timeout
        with self._cond:
            while number not in self._resets_done:
                if time.monotonic() > deadline:
                    self._check_alive()
                    raise TimeoutError(f"the simulation did not reset within {timeout:g} s")
                self._cond.wait(0.1)
        start = self.settings.start_pose

        def back(r: OdomReading) -> bool:
            near = abs(r.pose.x - start.x_m) < 0.01 and abs(r.pose.y - start.y_m) < 0.01
            return near and abs(r.linear_mps) < 0.01

        return self.wait_for_odom(back, timeout)

    def set_parameter(self, name: str, value: Any, timeout: float = 5.0) -> None:
        """Set a parameter of the /mujoco node (`paused`, `real_time_factor`)."""
        from rcl_interfaces.srv import SetParameters
        from rclpy.parameter import Parameter

        self._check_alive()
        client = self.session.node.create_client(SetParameters, "/mujoco/set_parameters")
        try:
            if not client.wait_for_service(timeout_sec=timeout):
                raise TimeoutError("/mujoco/set_parameters did not appear")
            message = Parameter(name, value=value).to_parameter_msg()
            request = SetParameters.Request(parameters=[message])
            result = self.session.wait_future(client.call_async(request), timeout).results[0]
        finally:
            self.session.node.destroy_client(client)
        if not result.successful:
            raise CourseError(f"Setting parameter failed: {result.reason}")

    def pause(self) -> None:
        """Stop the physics (simulated time stops)."""
        self.set_parameter("paused", True)

    def resume(self) -> None:
        """Run the physics again after pause()."""
        self.set_parameter("paused", False)

    def record(self, fps: int = 30) -> Any:
        """Start recording the robot's motion; `.save("run.html")` writes an offline replay."""
        from ..sim.view.recorder import Recorder
        from ..sim.world.model import build_model

        self._check_alive()
        return Recorder(self.session, build_model(self.settings), fps=fps)

    def show(self, height: int = 420) -> Any:
        """Display the live 3D view in the current output cell (and return it)."""
        if self.viewer is None:
            raise CourseError(
                "This world was started without a 3D view.",
                hint="start_world(show=True) starts one.",
            )
        return self.viewer.show(height)

    def stop(self, *, quiet: bool = False) -> None:
        """Stop the simulation and its 3D view (in a lab: the lab's, for every notebook).

        Says so in one line, unless `quiet` (the course's own clean-up after a failed start).
        """
        self.process.stop()
        if self.viewer is not None:
            self.viewer.stop()
        self.detach()
        if not quiet:
            whose = "Your lab's simulation" if self.shared else "The simulation"
            every = ", for every notebook of the lab" if self.shared else ""
            print(f"{whose} and its 3D view stopped{every}: `lesson.world()` starts them again.")

    def detach(self) -> None:
        """Stop listening to the world and let go of it, leaving it running; idempotent."""
        with _worlds_lock:
            if _worlds.get(id(self.session)) is self:
                del _worlds[id(self.session)]
        steps: list[tuple[Any, Any]] = [(self._feed.remove, self._on_samples)]
        if not self.session.closed:
            node = self.session.node
            steps += [
                (node.destroy_publisher, self._fresh),
                (node.destroy_publisher, self._reset),
                (node.destroy_subscription, self._reset_sub),
            ]
            if self._cmd is not None:
                steps.append((node.destroy_publisher, self._cmd))
        for undo, entity in steps:  # each step on its own: one failure skips no other
            try:
                undo(entity)
            except Exception:  # the session may be closing concurrently: said, not raised
                _log.debug("a step of the world handle's tear-down failed", exc_info=True)
