"""The simulation's instructor settings (config/simulation.yaml): start pose, obstacles, rates."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from ..core.paths import config_dir
from .loader import SettingValueError, load_settings, setting

__all__ = [
    "Camera",
    "Lidar",
    "Obstacle",
    "Rates",
    "SimulationSettings",
    "StartPose",
    "load_simulation_settings",
    "simulation_yaml",
]

_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class StartPose:
    """Where the robot stands after a start or a reset."""

    x_m: float = setting(0.0, help="x position on the floor (m)", ge=-4.5, le=4.5)
    y_m: float = setting(0.0, help="y position on the floor (m)", ge=-4.5, le=4.5)
    yaw_deg: float = setting(
        0.0, help="heading, counter-clockwise from the +x axis (degrees)", ge=-180, le=180
    )


@dataclass(frozen=True)
class Obstacle:
    """A fixed box or cylinder standing on the floor."""

    name: str = setting(help="a simple name (letters, digits, _), unique in the world")
    shape: Literal["box", "cylinder"] = setting(help="box or cylinder")
    position_m: tuple[float, float] = setting(help="the centre [x, y] on the floor (m)")
    size_m: tuple[float, ...] = setting(
        help="box: [length, width, height]; cylinder: [diameter, height] (m)"
    )
    yaw_deg: float = setting(0.0, help="turned counter-clockwise (degrees)", ge=-180, le=180)
    color: tuple[float, float, float] = setting((0.6, 0.6, 0.6), help="[red, green, blue], 0 to 1")

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

    clock_hz: float = setting(50.0, help="/clock", gt=0, le=1000)
    odom_hz: float = setting(50.0, help="/odom and /tf", gt=0, le=1000)
    joint_states_hz: float = setting(50.0, help="/joint_states", gt=0, le=1000)
    imu_hz: float = setting(50.0, help="/imu", gt=0, le=1000)
    scan_hz: float = setting(5.0, help="/scan", gt=0, le=100)
    camera_hz: float = setting(
        10.0, help="/camera/image_raw, only while something subscribes", gt=0, le=60
    )
    viewer_hz: float = setting(
        25.0,
        help="the 3D view, in wall-clock time (a divisor of odom_hz spaces its frames evenly)",
        gt=0,
        le=120,
    )


@dataclass(frozen=True)
class Lidar:
    """The LDS-01-like laser scanner: rays in one turn, counter-clockwise from straight ahead."""

    samples: int = setting(360, help="rays per turn", ge=4, le=1440)
    range_min_m: float = setting(0.12, help="nearest range measured (m)", gt=0, le=1)
    range_max_m: float = setting(3.5, help="farthest range measured (m)", gt=0, le=50)

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

    enabled: bool = setting(True, help="false on machines without EGL: the topics stay silent")
    width_px: int = setting(320, help="image width (pixels)", ge=16, le=1280)
    height_px: int = setting(240, help="image height (pixels)", ge=16, le=960)


DEFAULT_OBSTACLES = (
    Obstacle("obstacle_box", "box", (2.5, 0.0), (0.2, 0.6, 0.3), color=(0.8, 0.3, 0.2)),
    Obstacle("obstacle_cylinder", "cylinder", (-0.8, 0.9), (0.24, 0.4), color=(0.2, 0.5, 0.8)),
    Obstacle("obstacle_wall", "box", (0.2, -1.5), (2.4, 0.1, 0.3), color=(0.5, 0.5, 0.45)),
)


@dataclass(frozen=True)
class SimulationSettings:
    """Everything an instructor may change about the simulated world."""

    real_time_factor: float = setting(
        1.0,
        help="1.0 runs at real time, 2.0 twice as fast, 0 as fast as the machine can",
        ge=0,
        le=100,
    )
    timestep_s: float = setting(0.002, help="physics step (s); 0.002 is tested", gt=0, le=0.01)
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


def simulation_yaml() -> Path:
    """Return the path of simulation.yaml in the instructor's config folder."""
    return config_dir() / "simulation.yaml"


def load_simulation_settings(path: str | Path | None = None) -> SimulationSettings:
    """Read config/simulation.yaml (or `path`); a missing or empty file is a ConfigError."""
    return load_settings(Path(path) if path is not None else simulation_yaml(), SimulationSettings)
