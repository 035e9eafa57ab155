"""Fill the ROS messages of the simulated robot from its MuJoCo state (one object per topic)."""

from __future__ import annotations

import array
import math

from builtin_interfaces.msg import Time
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan

from ..world.model import WHEEL_JOINTS
from ..world.physics import Simulation

__all__ = ["Frames", "MessageFactory", "stamp_seconds", "to_stamp"]


def _sec_nanosec(seconds: float) -> tuple[int, int]:
    """Return `seconds` as a stamp's whole seconds and nanoseconds (to the nearest ns)."""
    return divmod(round(seconds * 1e9), 1_000_000_000)


def stamp_seconds(seconds: float) -> float:
    """Return simulated `seconds` as a reader computes them from the stamp `to_stamp` makes
    (sec + nanosec * 1e-9), without making the message."""
    sec, nanosec = _sec_nanosec(seconds)
    return sec + nanosec * 1e-9


def to_stamp(seconds: float) -> Time:
    """Return a builtin_interfaces/Time for simulated `seconds`."""
    sec, nanosec = _sec_nanosec(seconds)
    return Time(sec=sec, nanosec=nanosec)


class Frames:
    """The frame ids the messages carry (parameters of the nodes)."""

    def __init__(
        self,
        odom: str = "odom",
        base: str = "base_footprint",
        imu: str = "imu_link",
        scan: str = "base_scan",
    ) -> None:
        self.odom, self.base, self.imu, self.scan = odom, base, imu, scan


class MessageFactory:
    """Reuse one message per topic and refresh it from the simulation."""

    def __init__(self, sim: Simulation, frames: Frames) -> None:
        self.sim = sim
        self.frames = frames
        lidar = sim.settings.lidar
        self._scan = LaserScan()
        self._scan.angle_min = 0.0
        self._scan.angle_increment = 2.0 * math.pi / lidar.samples
        self._scan.angle_max = self._scan.angle_increment * (lidar.samples - 1)
        self._scan.range_min = lidar.range_min_m
        self._scan.range_max = lidar.range_max_m
        self._scan.scan_time = 1.0 / sim.settings.rates.scan_hz
        self._scan.time_increment = 0.0
        self._joints = JointState()
        self._joints.name = list(WHEEL_JOINTS)
        self._odom = Odometry()
        self._odom.header.frame_id = frames.odom
        self._odom.child_frame_id = frames.base
        self._imu = Imu()
        self._imu.header.frame_id = frames.imu
        self._clock = Clock()
        self.stamp = to_stamp(sim.time)

    def restamp(self) -> None:
        """Take the simulation's current time as the stamp of the next messages."""
        self.stamp = to_stamp(self.sim.time)

    def clock(self) -> Clock:
        """Return /clock for the current simulated time."""
        self._clock.clock = self.stamp
        return self._clock

    def odometry(self) -> Odometry:
        """Return /odom: ground-truth pose in `odom` and the twist in the robot's frame."""
        msg = self._odom
        msg.header.stamp = self.stamp
        position, quat = self.sim.base_pose3d()
        pose = msg.pose.pose
        pose.position.x, pose.position.y = float(position[0]), float(position[1])
        pose.position.z = 0.0
        pose.orientation.w, pose.orientation.x = float(quat[0]), float(quat[1])
        pose.orientation.y, pose.orientation.z = float(quat[2]), float(quat[3])
        linear, angular = self.sim.body_velocity()
        twist = msg.twist.twist
        twist.linear.x, twist.linear.y = float(linear[0]), float(linear[1])
        twist.angular.z = float(angular[2])
        return msg

    def sample_row(self) -> list[float]:
        """Return the robot's sample (world.samples.FIELDS): /odom's values and the wheels."""
        position, quat = self.sim.base_pose3d()
        linear, angular = self.sim.body_velocity()
        (left, right), _ = self.sim.wheels()
        stamp = self.stamp.sec + self.stamp.nanosec * 1e-9  # as a reader of /odom computes it
        return [
            stamp,
            float(position[0]),
            float(position[1]),
            *(float(q) for q in quat),
            float(linear[0]),
            float(angular[2]),
            left,
            right,
        ]

    def joint_states(self) -> JointState:
        """Return /joint_states for the two wheel joints."""
        (left, right), (left_v, right_v) = self.sim.wheels()
        msg = self._joints
        msg.header.stamp = self.stamp
        msg.position = [left, right]
        msg.velocity = [left_v, right_v]
        return msg

    def imu(self) -> Imu:
        """Return /imu from the last `sense()`."""
        reading = self.sim.imu()
        msg = self._imu
        msg.header.stamp = self.stamp
        o = msg.orientation
        o.w, o.x, o.y, o.z = reading.orientation
        g = msg.angular_velocity
        g.x, g.y, g.z = reading.angular_velocity
        a = msg.linear_acceleration
        a.x, a.y, a.z = reading.linear_acceleration
        return msg

    def scan(self) -> LaserScan:
        """Return /scan from the last `sense()` (inf where nothing is in range)."""
        msg = self._scan
        msg.header.stamp = self.stamp
        msg.header.frame_id = self.frames.scan
        msg.ranges = array.array("f", self.sim.scan().astype("float32").tobytes())
        return msg
