"""The `ros2` command family: one implementation behind the console command, magics and API.

Lesson 6 introduces it. Importing this package imports nothing else (a terminal command
loads only what its verb needs) and never rclpy; the verbs that talk to ROS use the
session's client node (course_lib.session) when they run.
"""

from __future__ import annotations

import importlib
import sys
import types
from typing import Any

_EXPORTS = {
    **dict.fromkeys(
        (
            "node_info",
            "node_list",
            "param_delete",
            "param_describe",
            "param_dump",
            "param_get",
            "param_list",
            "param_load",
            "param_set",
            "ros2",
            "topic_echo_once",
            "topic_list",
        ),
        "api",
    ),
    **dict.fromkeys(
        (
            "interface_show",
            "call_service",
            "service_list",
            "service_type",
            "topic_info",
            "topic_publish",
        ),
        "api_more",
    ),
    **dict.fromkeys(("NodeNotFoundError", "ParameterNotSetError", "TopicNotFoundError"), "errors"),
    "ParamFileError": "paramfile",
    **dict.fromkeys(
        ("CommandOutput", "Descriptor", "NodeInfo", "SetResult", "TopicInfo"), "results"
    ),
    **dict.fromkeys(("ParamValue", "parse_value"), "values"),
}

__all__ = sorted([*_EXPORTS, "client", "start_daemon"])


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def start_daemon(env):  # type: ignore[no-untyped-def]
    """Start the terminal commands' daemon for env's ROS_DOMAIN_ID (see ros2.daemon)."""
    from .daemon import start_daemon as _start

    return _start(env)


class _Package(types.ModuleType):
    """This package, whose `client` stays the API function once the module `client` loads."""

    @property
    def client(self) -> Any:
        """Return api.client (the import system would put module ros2.client here)."""
        from .api import client

        return client

    @client.setter
    def client(self, _module: Any) -> None:
        pass  # importing course_lib.ros2.client records it here; sys.modules keeps it


sys.modules[__name__].__class__ = _Package
