"""The `ros2` verbs as Python functions returning structured results (what lessons call).

`from course_lib.ros2 import api` gives them all: `api.param_get(...)`, `api.node_list()`,
`api.service_type(...)`; the modules hold them by family.
"""

from .errors import NodeNotFoundError, ParameterNotSetError, TopicNotFoundError
from .nodes_and_params import (
    ParamFileError,
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
from .services_and_topics import (
    call_service,
    interface_show,
    service_list,
    service_type,
    topic_info,
    topic_publish,
)

__all__ = [
    "NodeNotFoundError",
    "ParamFileError",
    "ParameterNotSetError",
    "TopicNotFoundError",
    "call_service",
    "client",
    "interface_show",
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
    "service_list",
    "service_type",
    "topic_echo_once",
    "topic_info",
    "topic_list",
    "topic_publish",
]
