"""ROS 2 parameters, interactively: the library behind the course's notebooks.

Names load on first use, so the `ros2` console command (which imports this package) starts
fast, and importing it never imports rclpy or mujoco.
"""

from __future__ import annotations

from importlib import import_module

_EXPORTS = {
    "CourseError": ".core.errors",
    "Session": ".session.session",
    "get_session": ".session.session",
    "launch": ".launch",
    "dry_run": ".launch",
    "CommandOutput": ".ros2",
    "ParamValue": ".ros2",
    "SetResult": ".ros2",
    "node_list": ".ros2",
    "param_describe": ".ros2",
    "param_dump": ".ros2",
    "param_get": ".ros2",
    "param_list": ".ros2",
    "param_set": ".ros2",
    "start_world": ".notebook.world_start",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> object:  # not `Any`: importing typing costs a `ros2` start
    if name not in _EXPORTS:
        raise AttributeError(f"module 'course_lib' has no attribute {name!r}")
    return getattr(import_module(_EXPORTS[name], __name__), name)


def __dir__() -> list[str]:
    return __all__
