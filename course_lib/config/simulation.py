"""The simulation's instructor settings (config/simulation.yaml): start pose, obstacles, rates."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from ..paths import CONFIG_DIR
from .loader import SettingValueError, load_settings, setting

__all__ = [
    "SIMULATION_YAML",
    "Camera",
    "Lidar",
    "Obstacle",
    "Rates",
    "SimulationSettings",
    "StartPose",
    "load_simulation_settings",
]

SIMULATION_YAML = CONFIG_DIR / "simulation.yaml"
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class StartPose:
    """Where the robot stands after a start or a reset."""

    x_m: float = setting(0.0, help="x position (m)", ge=-4.5, le=4.5)
    y_m: float = setting(0.0, help="y position (m)", ge=-4.5, le=4.5)
    yaw_deg: float = setting(0.0, help="heading, counter-clockwise from +x (degrees)")


@dataclass(frozen=True)
class Obstacle:
    """A fixed box or cylinder standing on the floor."""

    name: str
    shape: Literal["box", "cylinder"]
    position_m: tuple[float, float]
    size_m: tuple[float, ...]
    yaw_deg: float = 0.0
    color: tuple[float, float, float] = (0.6, 0.6, 0.6)

    def __post_init__(self) -> None:
        if not _NAME.match(self.name):
            raise SettingValueError(
                "name",
                f"{self.name!r} is not a simple name",
                "use letters, digits and underscores, like red_box.",
            )
        wanted = 3 if self.shape == "box" else 2
        layout = "[length, width, height]" if self.shape == "box" else "[diameter, height]"
        if len(self.size_m) != wanted:
            raise SettingValueError(
                "size_m",
                f"a {self.shape} needs {wanted} sizes, got {len(self.size_m)}",
                f"write size_m: {layout}.",
            )
        if min(self.size_m) <= 0:
            raise SettingValueError(
                "size_m",
                f"sizes must be positive, got {list(self.size_m)}",
                f"write size_m: {layout} in metres.",
            )
        if not all(0.0 <= c <= 1.0 for c in self.color):
            raise SettingValueError(
                "color",
                f"{list(self.color)} is not an RGB colour",
                "write three values between 0 and 1, like [0.8, 0.3, 0.2].",
            )


@dataclass(frozen=True)
class Rates:
    """How often each stream is published, in Hz of simulated time (viewer: wall time)."""

    clock_hz: float = setting(50.0, gt=0, le=1000)
    odom_hz: float = setting(50.0, gt=0, le=1000)
    joint_states_hz: float = setting(50.0, gt=0, le=1000)
    imu_hz: float = setting(50.0, gt=0, le=1000)
    scan_hz: float = setting(5.0, gt=0, le=100)
    camera_hz: float = setting(10.0, gt=0, le=60)
    viewer_hz: float = setting(50.0, gt=0, le=120)


@dataclass(frozen=True)
class Lidar:
    """The LDS-01-like laser scanner: rays in one turn, counter-clockwise from straight ahead."""

    samples: int = setting(360, ge=4, le=1440)
    range_min_m: float = setting(0.12, gt=0)
    range_max_m: float = setting(3.5, gt=0, le=50)

    def __post_init__(self) -> None:
        if self.range_min_m >= self.range_max_m:
            raise SettingValueError(
                "range_min_m",
                f"{self.range_min_m} is not below range_max_m ({self.range_max_m})",
                "make range_min_m smaller than range_max_m.",
            )


@dataclass(frozen=True)
class Camera:
    """The Raspberry Pi camera: rendered offscreen (EGL) only while someone subscribes."""

    enabled: bool = True
    width_px: int = setting(320, ge=16, le=1280)
    height_px: int = setting(240, ge=16, le=960)


DEFAULT_OBSTACLES = (
    Obstacle("obstacle_box", "box", (2.5, 0.0), (0.2, 0.6, 0.3), color=(0.8, 0.3, 0.2)),
    Obstacle("obstacle_cylinder", "cylinder", (-0.8, 0.9), (0.24, 0.4), color=(0.2, 0.5, 0.8)),
    Obstacle("obstacle_wall", "box", (0.2, -1.5), (2.4, 0.1, 0.3), color=(0.5, 0.5, 0.45)),
)


@dataclass(frozen=True)
class SimulationSettings:
    """Everything an instructor may change about the simulated world."""

    real_time_factor: float = setting(1.0, help="1 = real time; 0 = as fast as possible", ge=0)
    timestep_s: float = setting(0.002, help="physics step (s)", gt=0, le=0.01)
    start_pose: StartPose = StartPose()
    rates: Rates = Rates()
    lidar: Lidar = Lidar()
    camera: Camera = Camera()
    obstacles: tuple[Obstacle, ...] = DEFAULT_OBSTACLES

    def __post_init__(self) -> None:
        names = [o.name for o in self.obstacles]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise SettingValueError(
                "obstacles",
                f"the name {twice[0]!r} is used twice",
                "give every obstacle its own name.",
            )


def load_simulation_settings(path: str | Path | None = None) -> SimulationSettings:
    """Read config/simulation.yaml (or `path`); the defaults when the file does not exist."""
    if path is None:
        if not SIMULATION_YAML.exists():
            return SimulationSettings()
        path = SIMULATION_YAML
    return load_settings(path, SimulationSettings)
