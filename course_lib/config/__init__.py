"""Instructor settings: YAML files under config/ loaded into frozen dataclasses."""

from .loader import SettingValueError, load_settings, parse_settings, setting
from .simulation import (
    Camera,
    Lidar,
    Obstacle,
    Rates,
    SimulationSettings,
    StartPose,
    load_simulation_settings,
)

__all__ = [
    "Camera",
    "Lidar",
    "Obstacle",
    "Rates",
    "SettingValueError",
    "SimulationSettings",
    "StartPose",
    "load_settings",
    "load_simulation_settings",
    "parse_settings",
    "setting",
]
