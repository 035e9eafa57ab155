"""Put a ghost node into every listening client's ROS graph, as a node that has left can leave one.

The graph of rmw_fastrtps learns node names from the `ros_discovery_info` topic, one message per
participant. A message that arrives after its participant was removed re-adds the participant
with its nodes, and nothing removes them again (ros2/ros2#1413): `ros2 node list` shows a node
that no process runs. That race is rare and cannot be timed from outside, so this helper sends
such a message itself, naming a participant that does not exist. It writes on the same DDS
topic through rmw's own C API (rclpy would prefix the topic name), from a node of a private
context; the ghost stays in the clients that heard it after the helper is closed.
"""

from __future__ import annotations

import ctypes
import itertools
import time
from collections.abc import Callable
from typing import Any

import rclpy
from rmw_dds_common.msg import Gid, NodeEntitiesInfo, ParticipantEntitiesInfo

__all__ = ["make_ghost"]

_KEEP_LAST, _RELIABLE, _TRANSIENT_LOCAL, _AUTOMATIC = 1, 1, 1, 1
_serial = itertools.count(1)


class _Time(ctypes.Structure):
    _fields_ = [("sec", ctypes.c_uint64), ("nsec", ctypes.c_uint64)]


class _Qos(ctypes.Structure):  # rmw_qos_profile_t
    _fields_ = [
        ("history", ctypes.c_int),
        ("depth", ctypes.c_size_t),
        ("reliability", ctypes.c_int),
        ("durability", ctypes.c_int),
        ("deadline", _Time),
        ("lifespan", _Time),
        ("liveliness", ctypes.c_int),
        ("liveliness_lease_duration", _Time),
        ("avoid_ros_namespace_conventions", ctypes.c_bool),
    ]


class _PublisherOptions(ctypes.Structure):  # rmw_publisher_options_t
    _fields_ = [("payload", ctypes.c_void_p), ("unique_flows", ctypes.c_int)]


def _capsule(capsule: Any) -> int:
    get = ctypes.pythonapi.PyCapsule_GetPointer
    get.restype, get.argtypes = ctypes.c_void_p, [ctypes.py_object, ctypes.c_char_p]
    return get(capsule, None)


def make_ghost(domain_id: int, name: str, heard: Callable[[], bool], namespace: str = "/") -> None:
    """Make the running clients of `domain_id` list node `namespace`/`name` for good, held by
    no participant; return once `heard()` says it has arrived (the message is not kept)."""
    rcl = ctypes.CDLL("librcl.so")
    rmw = ctypes.CDLL("librmw_fastrtps_cpp.so")
    rcl.rcl_node_get_rmw_handle.restype = ctypes.c_void_p
    rcl.rcl_node_get_rmw_handle.argtypes = [ctypes.c_void_p]
    rmw.rmw_get_default_publisher_options.restype = _PublisherOptions
    rmw.rmw_create_publisher.restype = ctypes.c_void_p
    rmw.rmw_create_publisher.argtypes = (
        [ctypes.c_void_p] * 2 + [ctypes.c_char_p] + [ctypes.c_void_p] * 2
    )
    rmw.rmw_publish.argtypes = [ctypes.c_void_p] * 3
    rmw.rmw_destroy_publisher.argtypes = [ctypes.c_void_p] * 2

    meta = ParticipantEntitiesInfo.__class__
    meta.__import_type_support__()
    create = ctypes.CFUNCTYPE(ctypes.c_void_p)(_capsule(meta._CREATE_ROS_MESSAGE))
    convert = ctypes.PYFUNCTYPE(ctypes.c_bool, ctypes.py_object, ctypes.c_void_p)(
        _capsule(meta._CONVERT_FROM_PY)
    )
    destroy = ctypes.CFUNCTYPE(None, ctypes.c_void_p)(_capsule(meta._DESTROY_ROS_MESSAGE))

    context = rclpy.Context()
    context.init(domain_id=domain_id)
    node = rclpy.create_node("_ghost_maker", context=context)
    rmw_node = rcl.rcl_node_get_rmw_handle(node.handle.pointer)
    qos = _Qos(
        history=_KEEP_LAST,
        depth=1,
        reliability=_RELIABLE,
        durability=_TRANSIENT_LOCAL,
        liveliness=_AUTOMATIC,
        avoid_ros_namespace_conventions=True,
    )
    options = rmw.rmw_get_default_publisher_options()
    publisher = rmw.rmw_create_publisher(
        rmw_node,
        _capsule(meta._TYPE_SUPPORT),
        b"ros_discovery_info",
        ctypes.byref(qos),
        ctypes.byref(options),
    )
    assert publisher, "rmw_create_publisher failed"
    # A participant nobody runs: eProsima's vendor bytes, then bytes no live GUID has.
    gid = Gid(data=[1, 15, 0xEE, 0xEE, 0, 0, 0, 0, next(_serial), 0, 0, 0, 0, 0, 1, 0xC1])
    info = NodeEntitiesInfo(node_namespace=namespace, node_name=name)
    message = create()
    try:
        assert convert(ParticipantEntitiesInfo(gid=gid, node_entities_info_seq=[info]), message)
        assert rmw.rmw_publish(publisher, message, None) == 0, "rmw_publish failed"
    finally:
        destroy(message)
    try:
        # the clients must discover this participant before its message reaches them: 0.04-3 s
        # alone, and 10 s were once too short on 2 busy cores (a rerun, "no client listed")
        deadline = time.monotonic() + 30.0
        while not heard():
            assert time.monotonic() < deadline, f"no client listed the ghost {name}"
            time.sleep(0.02)
    finally:
        rmw.rmw_destroy_publisher(rmw_node, publisher)
        node.destroy_node()
        context.shutdown()
