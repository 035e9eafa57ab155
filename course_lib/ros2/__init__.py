"""The `ros2` command family: one implementation behind the console command, magics and API.

Lesson 6 introduces it. Importing this package never imports rclpy; the verbs that talk to
ROS use the session's client node (course_lib.session) when they run.
"""

from .api import (
    client,
    node_info,
    node_list,
    param_delete,
    param_describe,
    param_dump,
    param_get,
    param_list,
    param_load,
    param_set,
    ros2,
    topic_echo_once,
    topic_list,
)
from .errors import NodeNotFoundError, ParameterNotSetError, TopicNotFoundError
from .paramfile import ParamFileError
from .results import CommandOutput, Descriptor, NodeInfo, SetResult, TopicInfo
from .values import ParamValue, parse_value

__all__ = [
    "CommandOutput",
    "Descriptor",
    "NodeInfo",
    "NodeNotFoundError",
    "ParamFileError",
    "ParamValue",
    "ParameterNotSetError",
    "SetResult",
    "TopicInfo",
    "TopicNotFoundError",
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
    "parse_value",
    "ros2",
    "start_daemon",
    "topic_echo_once",
    "topic_list",
]


def start_daemon(env):  # type: ignore[no-untyped-def]
    """Start the terminal commands' daemon for env's ROS_DOMAIN_ID (see ros2.daemon)."""
    from .daemon import start_daemon as _start

    return _start(env)
