"""Build the MuJoCo world from the model folder and the instructor's simulation settings."""

from __future__ import annotations

import math
from pathlib import Path

import mujoco

from ...config.simulation import Obstacle, SimulationSettings
from ...core.paths import PACKAGE_DIR
from .kinematics import quat_from_yaw
from .robot import BASE_BODY, BASE_HEIGHT_M, SCAN_SITE, WHEEL_ACTUATORS, WHEEL_JOINTS

__all__ = [
    "BASE_BODY",
    "BASE_HEIGHT_M",
    "MODEL_DIR",
    "ROBOT_XML",
    "SCAN_SITE",
    "SCENE_XML",
    "WHEEL_ACTUATORS",
    "WHEEL_JOINTS",
    "build_model",
    "scan_sensor_name",
]

MODEL_DIR = PACKAGE_DIR / "models" / "turtlebot3_waffle_pi"
ROBOT_XML = MODEL_DIR / "turtlebot3_waffle_pi.xml"
SCENE_XML = MODEL_DIR / "scene.xml"
OBSTACLE_PREFIX = "obstacle_"


def scan_sensor_name(index: int) -> str:
    """Return the name of the rangefinder sensor of ray `index` (0 = straight ahead)."""
    return f"scan_{index:04d}"


def _replace_obstacles(spec: mujoco.MjSpec, obstacles: tuple[Obstacle, ...]) -> None:
    for body in list(spec.worldbody.bodies):
        if body.name.startswith(OBSTACLE_PREFIX):
            spec.delete(body)
    for obstacle in obstacles:
        height = obstacle.size_m[-1]
        x, y = obstacle.position_m
        body = spec.worldbody.add_body(
            name=obstacle.name,
            pos=[x, y, height / 2.0],
            quat=list(quat_from_yaw(math.radians(obstacle.yaw_deg))),
        )
        if obstacle.shape == "box":
            size = [obstacle.size_m[0] / 2.0, obstacle.size_m[1] / 2.0, height / 2.0]
            kind = mujoco.mjtGeom.mjGEOM_BOX
        else:
            size = [obstacle.size_m[0] / 2.0, height / 2.0, 0.0]
            kind = mujoco.mjtGeom.mjGEOM_CYLINDER
        body.add_geom(name=obstacle.name, type=kind, size=size, rgba=[*obstacle.color, 1.0])


def _add_lidar(spec: mujoco.MjSpec, samples: int) -> None:
    base = spec.body(BASE_BODY)
    origin = list(spec.site(SCAN_SITE).pos)
    for i in range(samples):
        angle = 2.0 * math.pi * i / samples
        site = base.add_site(name=f"lidar_ray_{i:04d}", pos=origin, group=5)
        site.alt.type = mujoco.mjtOrientation.mjORIENTATION_ZAXIS
        site.alt.zaxis = [math.cos(angle), math.sin(angle), 0.0]
        sensor = spec.add_sensor(
            name=scan_sensor_name(i),
            type=mujoco.mjtSensor.mjSENS_RANGEFINDER,
            objtype=mujoco.mjtObj.mjOBJ_SITE,
            objname=site.name,
        )
        sensor.intprm[0] = 1  # output the distance only


def build_spec(
    settings: SimulationSettings | None = None, scene: Path = SCENE_XML
) -> mujoco.MjSpec:
    """Return the world's MjSpec: scene.xml with the configured obstacles, pose and lidar."""
    settings = settings or SimulationSettings()
    spec = mujoco.MjSpec.from_file(str(scene))
    spec.option.timestep = settings.timestep_s
    pose = settings.start_pose
    base = spec.body(BASE_BODY)
    base.pos = [pose.x_m, pose.y_m, BASE_HEIGHT_M]
    base.quat = list(quat_from_yaw(math.radians(pose.yaw_deg)))
    _replace_obstacles(spec, settings.obstacles)
    _add_lidar(spec, settings.lidar.samples)
    return spec


def build_model(settings: SimulationSettings | None = None) -> mujoco.MjModel:
    """Compile the world for `settings` (the defaults of config/simulation.yaml if None)."""
    return build_spec(settings).compile()
