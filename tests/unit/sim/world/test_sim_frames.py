"""The robot's frames come from the MuJoCo model once and feed the URDF, /tf_static and /tf."""

from __future__ import annotations

import math

import mujoco
import pytest

from course_lib.sim.ros.urdf import robot_urdf
from course_lib.sim.world.frames import joint_transform, robot_frames
from course_lib.sim.world.model import build_model


@pytest.fixture(scope="module")
def model() -> mujoco.MjModel:
    return build_model()


def test_tree_starts_at_base_footprint_and_parents_come_first(model: mujoco.MjModel) -> None:
    joints = robot_frames(model)
    known = {"base_footprint"}
    for joint in joints:
        assert joint.parent in known, f"{joint.child} comes before its parent {joint.parent}"
        known.add(joint.child)
    assert [j.child for j in joints if not j.fixed] == ["wheel_left_link", "wheel_right_link"]
    assert {"base_scan", "imu_link", "camera_rgb_optical_frame"} <= known


def test_numbers_are_the_models(model: mujoco.MjModel) -> None:
    by_child = {j.child: j for j in robot_frames(model)}
    assert by_child["base_link"].origin.xyz == pytest.approx((0.0, 0.0, 0.010))
    assert by_child["base_scan"].origin.xyz == pytest.approx((-0.064, 0.0, 0.132))
    assert by_child["imu_link"].origin.xyz == pytest.approx((-0.032, 0.0, 0.068))
    assert by_child["wheel_left_link"].origin.xyz == pytest.approx((0.0, 0.1435, 0.023))
    assert by_child["wheel_left_link"].axis == (0.0, 1.0, 0.0)
    # the TurtleBot3 URDF's optical frame: rpy (-pi/2, 0, -pi/2), z along the view
    optical = by_child["camera_rgb_optical_frame"].origin.quat
    assert optical == pytest.approx((0.5, -0.5, 0.5, -0.5))


def test_a_wheel_turns_about_its_axis(model: mujoco.MjModel) -> None:
    wheel = next(j for j in robot_frames(model) if j.child == "wheel_left_link")
    turned = joint_transform(wheel, math.pi / 2)
    half = math.sqrt(0.5)
    assert turned.quat == pytest.approx((half, 0.0, half, 0.0))
    assert turned.xyz == wheel.origin.xyz


def test_urdf_has_every_frame_joint(model: mujoco.MjModel) -> None:
    urdf = robot_urdf(model)
    for joint in robot_frames(model):
        kind = "fixed" if joint.fixed else "continuous"
        assert f'<joint name="{joint.name}" type="{kind}">' in urdf
        assert f'<child link="{joint.child}"/>' in urdf
