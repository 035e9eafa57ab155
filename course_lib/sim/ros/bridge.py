"""Run the world: physics paced at real time, ROS topics and parameters, the live 3D view."""

from __future__ import annotations

import collections
import contextlib
import logging
import threading
import time
from typing import Any

from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rclpy.context import Context
from rclpy.executors import Executor, SingleThreadedExecutor
from rclpy.experimental import EventsExecutor
from rclpy.qos import DurabilityPolicy, QoSPolicyKind, QoSProfile, ReliabilityPolicy
from rclpy.qos_overriding_options import QoSOverridingOptions
from rclpy.serialization import deserialize_message
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, Imu, JointState, LaserScan
from std_msgs.msg import Empty, Float64MultiArray, String, UInt32

from ..world.frames import robot_frames
from ..world.pacing import Cadence, Pacer, Schedule
from ..world.physics import Simulation
from ..world.samples import REST_BATCH_S, SAMPLES_TOPIC
from .messages import Frames, MessageFactory, stamp_seconds
from .nodes import create_nodes, node_specs
from .sample_batches import SampleBatches
from .tf import TfFactory, TFMessage
from .topics import FRESH_TOPIC, RESET_DONE_TOPIC, RESET_TOPIC, reset_done_qos
from .urdf import robot_urdf

__all__ = ["RESET_DONE_TOPIC", "RESET_TOPIC", "Bridge"]

_LATCHED = QoSProfile(
    depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL, reliability=ReliabilityPolicy.RELIABLE
)
_SENSOR_QOS = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
# tf2_ros's broadcasters: /tf keeps 100, /tf_static is latched; both accept qos_overrides.
_TF_QOS = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
_OVERRIDABLE = QoSOverridingOptions(
    [
        QoSPolicyKind.DEPTH,
        QoSPolicyKind.DURABILITY,
        QoSPolicyKind.HISTORY,
        QoSPolicyKind.RELIABILITY,
    ]
)
_log = logging.getLogger(__name__)
# The node whose /cmd_vel arrives ten times a second waits in an executor and thread of its own:
# rclpy's SingleThreadedExecutor rebuilds its wait set from every entity of its nodes at each
# wake, in Python (0.019 cores with all nine nodes, 0.008 with this one alone), and rclpy's
# events executor (C++) does not (0.002). Its spin() busy-waits in rclpy 7.1.6, so the thread
# calls spin_once with a timeout. Only here: this node's entities never change while it spins
# (a client node that destroyed a subscription under the events executor crashed its process).
_DRIVE_NODE = "turtlebot3_diff_drive"
# The longest the drive's thread waits before it looks at _stop again: close() shuts its
# executor down, which ends the wait at once, so this only bounds a thread nobody closes (a
# wake a second cost a still world 0.0002 cores).
_EVENTS_WAIT_S = 30.0
# The loop sleeps through the points nobody reads (Bridge._doze), at most this long: the
# course's samples come every BATCH_S (0.1 s), or every REST_BATCH_S once the robot has rested
# REST_S; a moving robot that a 3D view shows wakes for each of the view's frames. A wake costs
# the world about 0.5 ms here, whatever it does: 50 a second were a third of a driving world's
# CPU. The pacer does not count a doze's lag as falling behind (its slack).
_DOZE_S = 0.1
_REST_DOZE_S = REST_BATCH_S


class Bridge:
    """Own the simulation's nodes and run the physics loop in the calling thread."""

    def __init__(self, sim: Simulation, context: Context, *, viewer: Any = None) -> None:
        self.sim = sim
        self.viewer = viewer
        settings = sim.settings
        self.urdf = robot_urdf(sim.model)
        self.nodes = create_nodes(context, node_specs(settings, sim.drive, self.urdf))
        self.messages = factory = MessageFactory(sim, Frames())
        self.tf = TfFactory(sim, robot_frames(sim.model))
        self._builders = {
            "clock": factory.clock,
            "odom": factory.odometry,
            "imu": factory.imu,
            "joint_states": factory.joint_states,
            "scan": factory.scan,
            "tf_odom": lambda: self.tf.odom(factory.stamp),
            "tf_wheels": lambda: self.tf.wheels(factory.stamp),
        }
        self._doze_slack = 0.0  # the lag (s) of the doze being caught up
        self.pacer = Pacer(settings.real_time_factor)
        self._view_period_s = 1.0 / settings.rates.viewer_hz
        self.paused = False
        self._inputs: collections.deque[tuple[str, Any]] = collections.deque()
        self._inputs_lock = threading.Lock()  # a command and a reset queue in one order
        self._holding: bytes | None = None  # the /cmd_vel message whose command holds
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._dozing = False  # the loop sleeps through points nobody reads (the robot rests)
        self._lagging = False  # ... and then catches up with the wall clock
        self.spin_error: BaseException | None = None  # why the ROS thread stopped, if it did
        self._publishers()
        mujoco_node = self.nodes["mujoco"]
        mujoco_node.add_post_set_parameters_callback(self._on_parameters)
        self.executors: dict[str, Executor] = {
            "sim-ros": SingleThreadedExecutor(context=context),
            "sim-drive": EventsExecutor(context=context),
        }
        for name, node in self.nodes.items():
            self.executors["sim-drive" if name == _DRIVE_NODE else "sim-ros"].add_node(node)
        self._spin_threads = [
            threading.Thread(target=self._spin, args=(executor,), name=name, daemon=True)
            for name, executor in self.executors.items()
        ]

    def _publishers(self) -> None:
        n = self.nodes
        self.pub = {
            "clock": n["mujoco"].create_publisher(
                Clock, "/clock", 10, qos_overriding_options=_OVERRIDABLE
            ),
            "odom": n["turtlebot3_diff_drive"].create_publisher(Odometry, "/odom", 10),
            "joint_states": n["turtlebot3_joint_state"].create_publisher(
                JointState, "/joint_states", 10
            ),
            "imu": n["turtlebot3_imu"].create_publisher(Imu, "/imu", 10),
            "scan": n["turtlebot3_laserscan"].create_publisher(LaserScan, "/scan", _SENSOR_QOS),
            # odom -> base_footprint comes from the drive (Gazebo's publish_odom_tf), the
            # wheels from robot_state_publisher: two publishers on /tf, as in the tutorial.
            "tf_odom": n["turtlebot3_diff_drive"].create_publisher(
                TFMessage, "/tf", _TF_QOS, qos_overriding_options=_OVERRIDABLE
            ),
            "tf_wheels": n["robot_state_publisher"].create_publisher(
                TFMessage, "/tf", _TF_QOS, qos_overriding_options=_OVERRIDABLE
            ),
        }
        self.camera = None
        if "camera_driver" in n:
            from .camera import CameraStream

            image_qos = QoSProfile(depth=2, reliability=ReliabilityPolicy.RELIABLE)
            publishers = (
                n["camera_driver"].create_publisher(Image, "/camera/image_raw", image_qos),
                n["camera_driver"].create_publisher(CameraInfo, "/camera/camera_info", image_qos),
            )
            self.camera = CameraStream(
                self.sim.model,
                self.sim.settings.camera,
                publishers,
                n["camera_driver"].get_logger(),
            )
        self._description = n["robot_state_publisher"].create_publisher(
            String, "/robot_description", _LATCHED, qos_overriding_options=_OVERRIDABLE
        )
        self._tf_static = n["robot_state_publisher"].create_publisher(
            TFMessage, "/tf_static", _LATCHED, qos_overriding_options=_OVERRIDABLE
        )
        n["turtlebot3_diff_drive"].create_subscription(
            Twist, "/cmd_vel", self._on_cmd_vel, 10, raw=True
        )
        n["mujoco"].create_subscription(UInt32, RESET_TOPIC, self._on_reset, 10)
        n["mujoco"].create_subscription(Empty, FRESH_TOPIC, self._on_fresh, 10)
        self._reset_done = n["mujoco"].create_publisher(UInt32, RESET_DONE_TOPIC, reset_done_qos())
        samples = n["mujoco"].create_publisher(Float64MultiArray, SAMPLES_TOPIC, 10)
        self.samples = SampleBatches(samples, self.sim.settings.rates.odom_hz)

    def _spin(self, executor: Executor) -> None:
        """Serve the nodes' callbacks; a callback's error stops the whole world, logged."""
        try:
            if not isinstance(executor, SingleThreadedExecutor):  # the events executor
                while not self._stop.is_set() and executor.context.ok():
                    executor.spin_once(timeout_sec=_EVENTS_WAIT_S)
            else:
                executor.spin()
        except Exception as err:
            if self._stop.is_set() or not executor.context.ok():
                return  # ends when the context shuts down
            self.spin_error = err
            _log.error("the simulation's ROS thread stopped", exc_info=err)
            self.stop()  # a world without its ROS callbacks would ignore every command

    def _on_cmd_vel(self, data: bytes) -> None:
        # Applied at the loop's next step, as Gazebo's drive applies it at its next update: no
        # early wake, which would step the physics ahead of the wall clock and publish early
        # (but a dozing loop, behind the wall clock, wakes to catch up to it and apply it).
        # The tutorial's node sends the same message ten times a second: a message equal to
        # the one whose command holds is not decoded again (0.07 ms of Python each).
        with self._inputs_lock:
            if data == self._holding:
                return
            msg = deserialize_message(data, Twist)
            twist = (msg.linear.x, msg.angular.z)
            self._inputs.append(("cmd", twist))
            self._holding = data
        if self._dozing and twist != self.sim.command_twist:
            self._wake.set()  # a new command to a resting robot: catch up, then apply it

    def _on_reset(self, msg: UInt32) -> None:
        with self._inputs_lock:
            self._inputs.append(("reset", msg.data))
            self._holding = None  # a reset stops the robot: the next command counts again
        self._wake.set()

    def _on_fresh(self, _msg: Empty) -> None:
        self._inputs.append(("fresh", None))
        self._wake.set()  # a dozing loop catches up first: the samples up to now go out

    def _on_parameters(self, parameters: list[Any]) -> None:
        for parameter in parameters:
            if parameter.name == "paused":
                self.paused = bool(parameter.value)
            elif parameter.name == "real_time_factor":
                self.pacer.set_factor(float(parameter.value))
        self.pacer.restart()
        self._wake.set()

    def stop(self) -> None:
        """Ask the loop to end (safe from a signal handler or another thread)."""
        self._stop.set()
        self._wake.set()

    def _publish(self, streams: list[str]) -> None:
        """Publish the streams due that someone reads: an unread message is never built."""
        if "camera" in streams:
            streams = [s for s in streams if s != "camera"]
            if self.camera is not None and self.camera.wanted:
                self.camera.offer(self.sim.time, self.sim.data.qpos)
        read = [name for name in streams if self.pub[name].get_subscription_count()]
        if "imu" in read or "scan" in read:
            self.sim.sense(scan="scan" in read)
        self.messages.restamp()
        for name in read:
            self.pub[name].publish(self._builders[name]())
        if "odom" in streams and self.samples.read:
            self.samples.add(self.messages.sample_row(), self.sim.time)

    def _apply_inputs(self) -> None:
        """Apply commands and resets in the order they arrived."""
        while self._inputs:
            kind, value = self._inputs.popleft()
            if kind == "cmd":
                self.sim.command(*value)
            elif kind == "fresh":
                self.samples.fresh(self.sim.time)
            else:
                self.sim.reset()
                self.pacer.restart()
                self.samples.note(still=False, now=self.sim.time)  # its rest starts anew
                self._publish(["odom", "joint_states", "tf_odom", "tf_wheels"])
                self.samples.flush()  # the start pose reaches the readers before the reply
                self._reset_done.publish(UInt32(data=value))

    def run(self, *, ready: Any = None, max_sim_time_s: float | None = None) -> None:
        """Step, publish and pace until stop(); call `ready()` once the world is up."""
        rates = self.sim.settings.rates
        schedule = Schedule(
            {
                "clock": rates.clock_hz,
                "odom": rates.odom_hz,
                "joint_states": rates.joint_states_hz,
                "tf_odom": rates.odom_hz,
                "tf_wheels": rates.joint_states_hz,
                "imu": rates.imu_hz,
                "scan": rates.scan_hz,
                "camera": rates.camera_hz,
            },
            self.sim.timestep,
            self.sim.time,
        )
        self._description.publish(String(data=self.urdf))
        self._tf_static.publish(self.tf.static(self.messages.stamp))
        for thread in self._spin_threads:
            thread.start()
        self._publish(schedule.advance(0))
        # A quarter of a physics wake's period of slack: the view's frames fall on every n-th
        # wake (25 Hz at 50 Hz), evenly spaced, however the wakes jitter.
        wake_period = self.sim.timestep * min(schedule.periods.values())
        view = Cadence(1.0 / rates.viewer_hz, slack_s=wake_period / 4)
        if ready is not None:
            ready()
        while not self._stop.is_set():
            if max_sim_time_s is not None and self.sim.time >= max_sim_time_s:
                break
            if self._lagging:  # after a doze: inputs wait until the points before them are done
                self._lagging = not self.paused and self._overdue(self.sim.time + wake_period / 2)
                if not self._lagging:
                    self._doze_slack = 0.0  # caught up: a lag from now on is a stall
            if not self._lagging:
                self._apply_inputs()
            if self.paused:
                self.samples.flush()
                self._wake.wait(0.1)
                self._wake.clear()
                continue
            if self._lagging and max_sim_time_s is None and self._catch_up_still(schedule):
                continue
            steps = schedule.steps_to_next()
            self.sim.advance(steps)  # a robot at rest with no command: only time passes
            self.samples.note(self.sim.still, self.sim.time)
            self._publish(schedule.advance(steps))
            if self.viewer is not None and view.due(time.monotonic()):
                self.viewer.update(self.sim.data)
            ahead = 0 if self._lagging else self._doze(schedule)
            if ahead:
                self._doze_slack = ahead * self.sim.timestep
            delay = self.pacer.delay(
                self.sim.time + ahead * self.sim.timestep,
                time.monotonic(),
                slack_s=self._doze_slack,
            )
            if delay > 0 and self._wake.wait(delay):
                self._wake.clear()
            self._dozing = False

    def _catch_up_still(self, schedule: Schedule) -> bool:
        """Take the points a resting robot dozed through, back to back, as the loop would,
        and return True; or take none and return False, unless the robot is still and nobody
        reads a stream but the course's samples.

        Only time passes then (inputs wait until the loop has caught up, as they do point by
        point): each odom point adds the same sample row with its own stamp, built once, and
        no other message is due. Point by point, the wake once a second of a resting world
        took about 3 ms for its fifty points.
        """
        camera = self.camera is not None and self.camera.wanted
        if not self.sim.still or self.samples.rest_since is None or camera:
            return False
        if any(publisher.get_subscription_count() for publisher in self.pub.values()):
            return False
        sampled = self.samples.read
        pose = self.messages.sample_row()[1:] if sampled else []  # the same at every point
        half_wake = self.sim.timestep * min(schedule.periods.values()) / 2
        while self._lagging and not (self.paused or self._stop.is_set()):
            steps = schedule.steps_to_next()
            self.sim.advance(steps)
            if "odom" in schedule.advance(steps) and sampled:
                self.samples.add([stamp_seconds(self.sim.time), *pose], self.sim.time)
            self._lagging = self._overdue(self.sim.time + half_wake)
        if not self._lagging:
            self._doze_slack = 0.0  # caught up: a lag from now on is a stall
        return True

    def _overdue(self, sim_time: float) -> bool:
        """Return True if simulated `sim_time` is already due on the wall clock (paced only)."""
        paced = self.pacer.real_time_factor > 0
        now = time.monotonic()
        return paced and self.pacer.delay(sim_time, now, slack_s=self._doze_slack) == 0

    def _doze(self, schedule: Schedule) -> int:
        """Return how many steps the loop may sleep through (0: wake at the next point).

        While nothing that is read falls due (no ROS reader of the world's streams: the
        course's own samples go out in batches), the points in between publish nothing: the
        loop sleeps until the one before the next that is read, then takes them back to back
        (stepping the physics of a moving robot), so each message leaves when it would have.
        A new command or a reset wakes it early (it catches up first). A moving robot that a
        3D view shows wakes for each of the view's frames.
        """
        camera = self.camera is not None and self.camera.wanted
        if self.paused or camera or self.pacer.real_time_factor <= 0:
            return 0
        self._dozing = True  # before looking at the inputs: a command from now on wakes us
        if self._inputs:
            self._dozing = False
            return 0
        seconds = _REST_DOZE_S if self.samples.resting(self.sim.time) else _DOZE_S
        if not self.sim.still and self.viewer is not None and self.viewer.watchers:
            seconds = min(seconds, self._view_period_s)
        limit = round(seconds / self.sim.timestep)
        read = [name for name, pub in self.pub.items() if pub.get_subscription_count()]
        due = [schedule.steps_until(read) if read else limit]
        if self.samples.read:
            rows_left = self.samples.rows_left(self.sim.time)
            odom = schedule.steps_until(["odom"]) + (rows_left - 1) * schedule.periods["odom"]
            due.append(odom)
        ahead = max(0, min([limit, *due]) - schedule.steps_to_next())
        self._lagging = self._dozing = ahead > 0
        return ahead

    def close(self) -> None:
        """Stop spinning and destroy the nodes (the caller shuts the context down)."""
        self._stop.set()
        if self.camera is not None:
            self.camera.close()
        for executor in self.executors.values():
            executor.shutdown(timeout_sec=2.0)
        for thread in self._spin_threads:
            if thread.is_alive():
                thread.join(timeout=2.0)
        for node in self.nodes.values():
            with contextlib.suppress(Exception):
                node.destroy_node()
