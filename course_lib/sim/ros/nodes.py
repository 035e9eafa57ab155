"""The simulation's ROS nodes, named and parameterised like the tutorial's Gazebo world.

`ros2 param list` shows /mujoco (in place of /gazebo), /turtlebot3_diff_drive,
/turtlebot3_joint_state, /turtlebot3_imu, /turtlebot3_laserscan and /robot_state_publisher,
each with the `qos_overrides.*` entries of its /parameter_events publisher (and /clock
subscription) as rclcpp nodes show them. Geometry and frames are read-only (they describe the
model); /mujoco's `paused` and `real_time_factor` may be set while the world runs.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
from rclpy.context import Context
from rclpy.node import Node
from rclpy.parameter import Parameter

from ...config.simulation import SimulationSettings
from ..world.kinematics import DiffDrive
from ..world.model import WHEEL_JOINTS
from .qos_parameters import declare_qos_parameters

__all__ = ["NodeSpec", "create_nodes", "node_specs"]


@dataclass(frozen=True)
class NodeSpec:
    """A node's name, whether it follows /clock, and its parameters (value, description)."""

    name: str
    use_sim_time: bool
    parameters: dict[str, tuple[Any, str]]
    writable: tuple[str, ...] = ()


def node_specs(settings: SimulationSettings, drive: DiffDrive, urdf: str) -> list[NodeSpec]:
    """Return the simulation's nodes and their parameters (pure data)."""
    rates = settings.rates
    lidar = settings.lidar
    return [
        NodeSpec(
            "mujoco",
            False,
            {
                "publish_rate": (rates.clock_hz, "/clock messages per simulated second"),
                "max_step_size": (settings.timestep_s, "fixed physics timestep (s)"),
                "real_time_factor": (
                    settings.real_time_factor,
                    "simulated seconds per wall second; 0 = as fast as possible",
                ),
                "paused": (False, "true stops the physics; /clock stops advancing"),
            },
            writable=("real_time_factor", "paused"),
        ),
        NodeSpec(
            "turtlebot3_diff_drive",
            True,
            {
                "update_rate": (rates.odom_hz, "/odom messages per simulated second"),
                "wheel_separation": (drive.wheel_separation_m, "distance between the wheels (m)"),
                "wheel_radius": (drive.wheel_radius_m, "wheel radius (m)"),
                "odometry_frame": ("odom", "frame_id of /odom"),
                "robot_base_frame": ("base_footprint", "child_frame_id of /odom"),
                "odometry_source": ("world", "odometry is MuJoCo's ground truth"),
                "publish_odom": (True, "publish /odom"),
                "publish_odom_tf": (True, "publish odom -> base_footprint on /tf"),
            },
        ),
        NodeSpec(
            "turtlebot3_joint_state",
            True,
            {
                "update_rate": (
                    rates.joint_states_hz,
                    "/joint_states messages per simulated second",
                ),
                "joint_names": (list(WHEEL_JOINTS), "joints in /joint_states"),
            },
        ),
        NodeSpec(
            "turtlebot3_imu",
            True,
            {
                "update_rate": (rates.imu_hz, "/imu messages per simulated second"),
                "frame_name": ("imu_link", "frame_id of /imu"),
            },
        ),
        NodeSpec(
            "turtlebot3_laserscan",
            True,
            {
                "update_rate": (rates.scan_hz, "/scan messages per simulated second"),
                "frame_name": ("base_scan", "frame_id of /scan"),
                "samples": (lidar.samples, "rays per turn"),
                "range_min": (lidar.range_min_m, "shortest range (m)"),
                "range_max": (lidar.range_max_m, "longest range (m)"),
            },
        ),
        *_camera_spec(settings),
        NodeSpec(
            "robot_state_publisher",
            True,
            {
                "robot_description": (urdf, "URDF of the robot, also on /robot_description"),
                "publish_frequency": (
                    rates.joint_states_hz,
                    "Hz of the wheels' transforms on /tf (one per /joint_states message)",
                ),
                "use_tf_static": (True, "fixed frames go on /tf_static (transient local), once"),
                "ignore_timestamp": (
                    False,
                    "false: only joint states newer than the last ones move the wheels' frames",
                ),
                "frame_prefix": ("", "prefix for frame ids"),
            },
        ),
    ]


def _camera_spec(settings: SimulationSettings) -> list[NodeSpec]:
    camera = settings.camera
    if not camera.enabled:
        return []
    return [
        NodeSpec(
            "camera_driver",
            True,
            {
                "update_rate": (
                    settings.rates.camera_hz,
                    "frames per simulated second, when subscribed",
                ),
                "image_width": (camera.width_px, "pixels"),
                "image_height": (camera.height_px, "pixels"),
                "camera_name": ("camera", "topics /camera/image_raw and /camera/camera_info"),
                "frame_name": ("camera_rgb_optical_frame", "frame_id of the images"),
            },
        )
    ]


def _descriptor(name: str, description: str, spec: NodeSpec) -> ParameterDescriptor:
    descriptor = ParameterDescriptor(
        name=name, description=description, read_only=name not in spec.writable
    )
    if name == "real_time_factor":
        descriptor.floating_point_range = [FloatingPointRange(from_value=0.0, to_value=100.0)]
    return descriptor


def _drop_own_clock_subscription(node: Node) -> None:
    """Keep `use_sim_time: true` but stop the node listening to its own process's /clock.

    These nodes stamp messages with MuJoCo's time directly and never read their ROS clock;
    five in-process /clock subscriptions halved the faster-than-real-time speed (53x -> 25x).
    Only public calls: the node's subscriptions and destroy_subscription (rclpy's time source
    keeps a handle it never uses again; tests/integration/sim/test_sim_nodes_clock.py checks the
    graph shows no /clock subscriber on these nodes).
    """
    for subscription in list(node.subscriptions):
        if subscription.topic_name == "/clock":
            node.destroy_subscription(subscription)


def create_nodes(context: Context, specs: list[NodeSpec]) -> dict[str, Node]:
    """Create every node with its declared parameters, in `context`."""
    nodes: dict[str, Node] = {}
    for spec in specs:
        node = Node(
            spec.name,
            context=context,
            parameter_overrides=[Parameter("use_sim_time", value=spec.use_sim_time)],
        )
        for name, (value, description) in spec.parameters.items():
            node.declare_parameter(name, value, _descriptor(name, description, spec))
        declare_qos_parameters(node, "/parameter_events", "publisher")
        declare_qos_parameters(node, "/clock", "subscription")
        _drop_own_clock_subscription(node)
        nodes[spec.name] = node
    return nodes
