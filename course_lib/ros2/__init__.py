"""The `ros2` command family: one implementation behind the console command, magics and API.

Lesson 6 introduces it. Importing this package imports nothing else (a terminal command
loads only what its verb needs) and never rclpy; the verbs that talk to ROS use the
session's client node (course_lib.session.session) when they run.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping

TYPE_CHECKING = False  # as typing's, without importing typing: the terminal's `ros2` starts light
if TYPE_CHECKING:
    from ..processes.children import ChildProcess

_EXPORTS = {
    **dict.fromkeys(
        (
            "client",
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
        "api.nodes_and_params",
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
        "api.services_and_topics",
    ),
    **dict.fromkeys(
        ("NodeNotFoundError", "ParameterNotSetError", "TopicNotFoundError"), "api.errors"
    ),
    "ParamFileError": "paramfile",
    **dict.fromkeys(
        ("CommandOutput", "Descriptor", "NodeInfo", "SetResult", "TopicInfo"), "results"
    ),
    **dict.fromkeys(("ParamValue", "parse_value"), "values"),
}

__all__ = sorted([*_EXPORTS, "start_daemon"])


def __getattr__(name: str) -> object:  # not `Any`: importing typing costs a `ros2` start
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def start_daemon(env: Mapping[str, str]) -> ChildProcess:
    """Start the terminal commands' daemon for env's ROS_DOMAIN_ID (see ros2.command.daemon)."""
    from .command.daemon import start_daemon as _start

    return _start(env)
