"""/tf and /tf_static from the simulation, in tf2_msgs built by the course (issue 12)."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from course_lib.core.waiting import wait_until
from course_lib.notebook import World, start_world
from course_lib.session.session import Session, get_session
from course_lib.sim.world.frames import joint_transform, robot_frames
from course_lib.sim.world.model import build_model

pytestmark = [pytest.mark.ros, pytest.mark.sim]

JAZZY_TF_MESSAGE_HASH = "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087"
# The tutorial's `ros2 topic list`, but /performance_metrics (Gazebo's own message).
TUTORIAL_TOPICS = [
    *("/camera/camera_info", "/camera/image_raw", "/clock", "/cmd_vel", "/imu"),
    *("/joint_states", "/odom", "/parameter_events", "/robot_description", "/rosout"),
    *("/scan", "/tf", "/tf_static"),
]
QOS = ("depth", "durability", "history", "reliability")
PARAMETER_EVENTS = [f"qos_overrides./parameter_events.publisher.{p}" for p in QOS]
CLOCK_SUBSCRIPTION = [f"qos_overrides./clock.subscription.{p}" for p in QOS]
# Names the tutorial's `ros2 param list` shows for each node's counterpart.
TUTORIAL_PARAMETERS = {
    "mujoco": ["publish_rate", "use_sim_time", *PARAMETER_EVENTS]
    + [f"qos_overrides./clock.publisher.{p}" for p in QOS],
    "robot_state_publisher": [
        "frame_prefix",
        "ignore_timestamp",
        "publish_frequency",
        "robot_description",
        "use_sim_time",
        "use_tf_static",
        *PARAMETER_EVENTS,
        *CLOCK_SUBSCRIPTION,
    ],
    **{
        name: ["use_sim_time", *PARAMETER_EVENTS, *CLOCK_SUBSCRIPTION]
        for name in (
            "turtlebot3_diff_drive",
            "turtlebot3_joint_state",
            "turtlebot3_imu",
            "turtlebot3_laserscan",
            "camera_driver",
        )
    },
}


def _wait_until(predicate: Callable[[], Any], timeout: float = 10.0) -> Any:
    return wait_until(predicate, timeout, message="condition not met")


@pytest.fixture(scope="module")
def own_session() -> Iterator[Session]:
    """The process's own session, so the in-process `ros2` door sees the world too."""
    session = get_session()
    yield session
    session.close()


@pytest.fixture(scope="module")
def world(own_session: Session) -> Iterator[World]:
    started = start_world(own_session, show=False, real_time_factor=4.0)
    yield started
    started.stop()


def _collect(session: Session, kind: type, topic: str, qos: Any) -> list[Any]:
    box: list[Any] = []
    session.node.create_subscription(kind, topic, box.append, qos)
    return box


def _stamp(header: Any) -> int:
    return header.stamp.sec * 1_000_000_000 + header.stamp.nanosec


def _latched() -> Any:
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

    return QoSProfile(
        depth=1,
        durability=DurabilityPolicy.TRANSIENT_LOCAL,
        reliability=ReliabilityPolicy.RELIABLE,
    )


def test_tutorial_topics_are_all_there(own_session: Session, world: World) -> None:
    def names() -> set[str]:
        return {n for n, _ in own_session.node.get_topic_names_and_types()}

    _wait_until(lambda: names() >= set(TUTORIAL_TOPICS))
    types = dict(own_session.node.get_topic_names_and_types())
    assert types["/tf"] == ["tf2_msgs/msg/TFMessage"]
    assert types["/tf_static"] == ["tf2_msgs/msg/TFMessage"]


def test_tf_type_hash_is_jazzys(own_session: Session, world: World) -> None:
    # two publishers: the drive (odom -> base_footprint) and robot_state_publisher (wheels)
    def publishers() -> Any:
        found = own_session.node.get_publishers_info_by_topic("/tf")
        named = len(found) == 2 and all(i.node_name != "_NODE_NAME_UNKNOWN_" for i in found)
        return found if named else None

    infos = _wait_until(publishers)
    assert {str(info.topic_type_hash) for info in infos} == {JAZZY_TF_MESSAGE_HASH}
    assert {info.node_name for info in infos} == {"turtlebot3_diff_drive", "robot_state_publisher"}


def test_tf_static_holds_the_models_fixed_frames(own_session: Session, world: World) -> None:
    from tf2_msgs.msg import TFMessage

    box = _collect(own_session, TFMessage, "/tf_static", _latched())
    message = _wait_until(lambda: box and box[-1])  # transient local: sent before we asked
    got = {(t.header.frame_id, t.child_frame_id): t.transform for t in message.transforms}
    fixed = [j for j in robot_frames(build_model()) if j.fixed]
    assert set(got) == {(j.parent, j.child) for j in fixed}
    assert {
        ("base_footprint", "base_link"),
        ("base_link", "base_scan"),
        ("base_link", "imu_link"),
        ("camera_rgb_frame", "camera_rgb_optical_frame"),
    } <= set(got)
    scan = got[("base_link", "base_scan")].translation
    assert (scan.x, scan.y, scan.z) == pytest.approx((-0.064, 0.0, 0.132))
    optical = got[("camera_rgb_frame", "camera_rgb_optical_frame")].rotation
    assert (optical.w, optical.x, optical.y, optical.z) == pytest.approx((0.5, -0.5, 0.5, -0.5))


def test_odom_to_base_footprint_matches_odom(own_session: Session, world: World) -> None:
    from nav_msgs.msg import Odometry
    from tf2_msgs.msg import TFMessage

    tf_box = _collect(own_session, TFMessage, "/tf", 100)
    odom_box = _collect(own_session, Odometry, "/odom", 100)
    start = world.odom().time_s
    world.drive(0.2, 0.4)
    try:
        world.wait_sim_time(start + 1.0)

        def pair() -> Any:
            poses = {_stamp(m.header): m.pose.pose for m in list(odom_box)}
            for message in list(tf_box):
                for t in message.transforms:
                    if (t.header.frame_id, t.child_frame_id) == ("odom", "base_footprint"):
                        pose = poses.get(_stamp(t.header))
                        if pose is not None and pose.position.x > 0.05:
                            return t.transform, pose
            return None

        transform, pose = _wait_until(pair)
    finally:
        world.drive(0.0, 0.0)
    p, q = pose.position, pose.orientation
    t, r = transform.translation, transform.rotation
    assert (t.x, t.y, t.z) == (p.x, p.y, p.z)
    assert (r.w, r.x, r.y, r.z) == (q.w, q.x, q.y, q.z)


def test_wheel_frames_follow_joint_states(own_session: Session, world: World) -> None:
    from sensor_msgs.msg import JointState
    from tf2_msgs.msg import TFMessage

    tf_box = _collect(own_session, TFMessage, "/tf", 100)
    joint_box = _collect(own_session, JointState, "/joint_states", 100)
    start = world.odom().time_s
    world.drive(0.2, 0.0)
    try:
        world.wait_sim_time(start + 0.5)
        wheels = {j.child: j for j in robot_frames(build_model()) if not j.fixed}

        def pair() -> Any:
            states = {_stamp(m.header): m for m in list(joint_box)}
            for message in list(tf_box):
                for t in message.transforms:
                    state = states.get(_stamp(t.header))
                    if t.child_frame_id == "wheel_left_link" and state and state.position[0]:
                        return t.transform, state
            return None

        transform, state = _wait_until(pair)
    finally:
        world.drive(0.0, 0.0)
    expected = joint_transform(wheels["wheel_left_link"], state.position[0])
    r = transform.rotation
    assert (r.w, r.x, r.y, r.z) == pytest.approx(expected.quat)
    assert abs(math.degrees(2 * math.acos(min(1.0, abs(r.w))))) > 0.0


@pytest.mark.parametrize("node", sorted(TUTORIAL_PARAMETERS))
def test_sim_nodes_list_the_tutorials_parameter_names(
    own_session: Session, world: World, node: str
) -> None:
    from course_lib.ros2.api import nodes_and_params as api

    listing = api.ros2(f"ros2 param list /{node}")
    assert listing.exit_code == 0, listing.stderr
    names = [line.strip() for line in listing.stdout.splitlines()]
    missing = [name for name in TUTORIAL_PARAMETERS[node] if name not in names]
    assert not missing, f"/{node} lacks {missing}"


def test_qos_override_values_are_the_ones_in_use(own_session: Session, world: World) -> None:
    from course_lib.ros2.api import nodes_and_params as api

    assert api.param_get("/robot_state_publisher", "use_tf_static").value is True
    assert api.param_get("/turtlebot3_diff_drive", "publish_odom_tf").value is True
    prefix = "qos_overrides./clock.subscription."
    assert api.param_get("/turtlebot3_imu", prefix + "reliability").value == "best_effort"
    assert api.param_get("/turtlebot3_imu", prefix + "depth").value == 1
    prefix = "qos_overrides./parameter_events.publisher."
    assert api.param_get("/mujoco", prefix + "depth").value == 1000
    prefix = "qos_overrides./tf_static.publisher."
    assert (
        api.param_get("/robot_state_publisher", prefix + "durability").value == "transient_local"
    )


def test_ros2_topic_echo_tf_once(own_session: Session, world: World) -> None:
    from course_lib.ros2.api import nodes_and_params as api

    echo = api.ros2("ros2 topic echo /tf --once")
    assert echo.exit_code == 0, echo.stderr
    assert echo.stdout.startswith("transforms:\n- header:\n")
    assert "child_frame_id: " in echo.stdout and echo.stdout.endswith("---\n")


def test_ros2_topic_echo_tf_once_in_a_terminal(own_session: Session, world: World) -> None:
    from course_lib.ros2 import start_daemon
    from course_lib.ros2.node.connect import daemon_socket

    daemon = start_daemon(own_session.env)
    try:
        _wait_until(lambda: os.path.exists(daemon_socket(own_session.domain_id)), 15)
        done = subprocess.run(
            [
                sys.executable,
                "-m",
                "course_lib.ros2.command.cli",
                "topic",
                "echo",
                "/tf",
                "--once",
            ],
            env=own_session.env,
            capture_output=True,
            text=True,
            timeout=60,
            check=False,
        )
    finally:
        daemon.stop()
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("transforms:\n- header:\n")
    assert "child_frame_id: base_footprint" in done.stdout or "wheel_left_link" in done.stdout
