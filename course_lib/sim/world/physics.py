"""The MuJoCo physics of the world: commands in, state and sensor readings out (no ROS)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import mujoco
import numpy as np

from ...config.simulation import SimulationSettings
from .kinematics import DiffDrive, Pose2D, yaw_from_quat
from .model import BASE_BODY, WHEEL_ACTUATORS, WHEEL_JOINTS, build_model, scan_sensor_name

__all__ = ["ImuReading", "Simulation"]

_SENSORS_OFF = int(mujoco.mjtDisableBit.mjDSBL_SENSOR)
# At rest: every joint slower than this (m/s, rad/s) and accelerating less than _REST_QACC.
# A robot left still settles below 1e-8 and 1e-6 within 0.5 s of simulated time (its numbers
# then wander at the solver's noise, ~5e-10 and ~1e-7); a reset's first step has qacc ~40.
_REST_QVEL = 1e-7
_REST_QACC = 1e-5


def _vector(values: Any) -> tuple[float, float, float]:
    """Return three numbers of a sensor array as floats."""
    x, y, z = (float(v) for v in values)
    return x, y, z


@dataclass(frozen=True)
class ImuReading:
    """IMU sample in the imu_link frame: orientation (w, x, y, z), rad/s, m/s^2."""

    orientation: tuple[float, float, float, float]
    angular_velocity: tuple[float, float, float]
    linear_acceleration: tuple[float, float, float]


class Simulation:
    """Step the TurtleBot3 world with a fixed timestep; sensors are computed on demand."""

    def __init__(self, settings: SimulationSettings | None = None) -> None:
        self.settings = settings or SimulationSettings()
        self.model = build_model(self.settings)
        self.data = mujoco.MjData(self.model)
        # Rangefinders cost more than the physics: compute them only when asked (sense()).
        self.model.opt.disableflags |= _SENSORS_OFF
        self.drive = self._measure_drive()
        self._base = self.model.body(BASE_BODY).id
        self._wheel_qpos = [self.model.joint(j).qposadr[0] for j in WHEEL_JOINTS]
        self._wheel_dof = [self.model.joint(j).dofadr[0] for j in WHEEL_JOINTS]
        self._actuators = [self.model.actuator(a).id for a in WHEEL_ACTUATORS]
        count = self.settings.lidar.samples
        self._scan_adr = np.array(
            [self.model.sensor(scan_sensor_name(i)).adr[0] for i in range(count)]
        )
        self._imu = {
            name: self.model.sensor(name).adr[0]
            for name in ("imu_accel", "imu_gyro", "imu_orientation")
        }
        self._imu_site = self.model.site("imu_link").id
        self.command_twist = (0.0, 0.0)
        self.still = False  # at rest since the last step, and nothing changed since (advance)
        mujoco.mj_forward(self.model, self.data)

    def _measure_drive(self) -> DiffDrive:
        """Read wheel radius and separation from the model itself (no second copy of numbers)."""
        left, right = (self.model.body(j.replace("_joint", "_link")) for j in WHEEL_JOINTS)
        radius = float(self.model.geom("wheel_left").size[0])
        return DiffDrive(radius, float(abs(left.pos[1] - right.pos[1])))

    @property
    def time(self) -> float:
        """Return the simulated time in seconds."""
        return float(self.data.time)

    @property
    def timestep(self) -> float:
        """Return the fixed physics step in seconds."""
        return float(self.model.opt.timestep)

    def command(self, linear_mps: float, angular_radps: float) -> None:
        """Set the body twist to follow (like a /cmd_vel message); held until the next one."""
        if (linear_mps, angular_radps) != self.command_twist:
            self.still = False
        self.command_twist = (float(linear_mps), float(angular_radps))
        left, right = self.drive.wheel_speeds(*self.command_twist)
        self.data.ctrl[self._actuators[0]] = left
        self.data.ctrl[self._actuators[1]] = right

    def step(self, steps: int = 1) -> None:
        """Advance the physics by `steps` fixed timesteps."""
        self.still = False
        mujoco.mj_step(self.model, self.data, nstep=steps)

    def advance(self, steps: int) -> None:
        """Advance by `steps` timesteps; a robot at rest with no command only sees time pass.

        Its physics would leave it where it is (within the solver's noise, 1e-10 m/s): the
        running world skips those steps, which cost a still lab about 0.01 cores. A new
        command or a reset (qacc of a robot not yet settled) makes it step again.
        """
        if not self.still:
            self.step(steps)
            self.still = self.at_rest()
            return
        # MuJoCo's own sum, step by step (the same stamps as stepping), on a Python float:
        # the same double additions, without 500 MjData attribute writes a second (0.0015
        # cores of a still world)
        timestep = float(self.model.opt.timestep)
        now = float(self.data.time)
        for _ in range(steps):
            now += timestep
        self.data.time = now

    def at_rest(self) -> bool:
        """Return True if the robot has no command and neither moves nor accelerates."""
        return (
            self.command_twist == (0.0, 0.0)
            and float(np.max(np.abs(self.data.qvel))) < _REST_QVEL
            and float(np.max(np.abs(self.data.qacc))) < _REST_QACC
        )

    def run_for(self, seconds: float) -> None:
        """Advance by the whole number of steps closest to `seconds` of simulated time."""
        self.step(max(0, round(seconds / self.timestep)))

    def reset(self, *, keep_time: bool = True) -> None:
        """Put the robot back at its start pose, at rest; simulated time keeps running."""
        now = self.data.time
        mujoco.mj_resetData(self.model, self.data)
        if keep_time:
            self.data.time = now
        self.still = False
        self.command(0.0, 0.0)
        mujoco.mj_forward(self.model, self.data)

    def sense(self, *, scan: bool = True) -> None:
        """Compute the IMU, and the rangefinders too if `scan` (they cost most), for now."""
        if scan:
            self.model.opt.disableflags &= ~_SENSORS_OFF
            mujoco.mj_forward(self.model, self.data)
            self.model.opt.disableflags |= _SENSORS_OFF
            return
        mujoco.mj_forward(self.model, self.data)
        self.model.opt.disableflags &= ~_SENSORS_OFF
        mujoco.mj_sensorVel(self.model, self.data)  # gyro
        mujoco.mj_sensorAcc(self.model, self.data)  # accelerometer
        self.model.opt.disableflags |= _SENSORS_OFF

    def pose(self) -> Pose2D:
        """Return the robot's pose on the floor (base_footprint in the world frame)."""
        x, y = self.data.xpos[self._base][:2]
        return Pose2D(float(x), float(y), yaw_from_quat(*self.data.xquat[self._base]))

    def base_pose3d(self) -> tuple[np.ndarray, np.ndarray]:
        """Return base_link position (x, y, z) and orientation (w, x, y, z) in the world."""
        return self.data.qpos[0:3].copy(), self.data.qpos[3:7].copy()

    def twist(self) -> tuple[float, float]:
        """Return MuJoCo's own (forward speed m/s, yaw rate rad/s) of the robot body."""
        rotation = self.data.xmat[self._base].reshape(3, 3)
        linear_body = rotation.T @ self.data.qvel[0:3]
        angular_world = rotation @ self.data.qvel[3:6]
        return float(linear_body[0]), float(angular_world[2])

    def body_velocity(self) -> tuple[np.ndarray, np.ndarray]:
        """Return linear and angular velocity of base_link in its own frame."""
        rotation = self.data.xmat[self._base].reshape(3, 3)
        return rotation.T @ self.data.qvel[0:3], self.data.qvel[3:6].copy()

    def wheels(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """Return the wheel joints' (positions rad, velocities rad/s), left then right."""
        q = self.data.qpos
        v = self.data.qvel
        pos = (float(q[self._wheel_qpos[0]]), float(q[self._wheel_qpos[1]]))
        return pos, (float(v[self._wheel_dof[0]]), float(v[self._wheel_dof[1]]))

    def scan(self) -> np.ndarray:
        """Return the lidar ranges (m) from the last sense(); inf where nothing is in range."""
        ranges = self.data.sensordata[self._scan_adr].copy()
        lidar = self.settings.lidar
        ranges[(ranges < 0) | (ranges > lidar.range_max_m)] = math.inf
        return ranges

    def imu(self) -> ImuReading:
        """Return the IMU reading from the last sense() (orientation of the imu_link site)."""
        s = self.data.sensordata
        a, g = self._imu["imu_accel"], self._imu["imu_gyro"]
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, self.data.site_xmat[self._imu_site])
        w, x, y, z = (float(q) for q in quat)
        return ImuReading((w, x, y, z), _vector(s[g : g + 3]), _vector(s[a : a + 3]))

    def warnings(self) -> dict[str, int]:
        """Return MuJoCo's warning counters that are not zero, by name."""
        return {
            mujoco.mjtWarning(i).name: int(w.number)
            for i, w in enumerate(self.data.warning)
            if w.number
        }
