"""The MuJoCo model itself: real physics, fixed steps, no ROS."""

from __future__ import annotations

import math

import mujoco
import pytest

from course_lib.config import SimulationSettings, StartPose
from course_lib.sim.world.model import ROBOT_XML, SCENE_XML
from course_lib.sim.world.physics import Simulation

pytestmark = pytest.mark.sim

BOX_FACE_X = 2.4  # the default obstacle_box spans x 2.4..2.6, y -0.3..0.3
LIDAR_X = -0.064  # base_scan in base_link


@pytest.fixture
def sim() -> Simulation:
    return Simulation()


@pytest.mark.parametrize("path", [ROBOT_XML, SCENE_XML])
def test_model_files_load_on_their_own(path) -> None:
    model = mujoco.MjModel.from_xml_path(str(path))
    assert model.nu == 2


def test_steps_with_fixed_controls_without_warnings(sim: Simulation) -> None:
    sim.command(0.2, 0.3)
    sim.run_for(3.0)
    sim.command(-0.2, -1.0)
    sim.run_for(2.0)
    assert sim.warnings() == {}


def test_wheel_geometry_comes_from_the_model(sim: Simulation) -> None:
    assert sim.drive.wheel_radius_m == pytest.approx(0.033)
    assert sim.drive.wheel_separation_m == pytest.approx(0.287)
    assert sim.model.body("base_link").subtreemass[0] == pytest.approx(1.8, abs=0.05)


def test_forward_command_gives_the_commanded_speed(sim: Simulation) -> None:
    sim.command(0.2, 0.0)
    sim.run_for(1.0)
    speed, yaw_rate = sim.twist()
    assert speed == pytest.approx(0.2, abs=0.01)
    assert abs(yaw_rate) < 0.01
    assert sim.pose().x == pytest.approx(0.195, abs=0.01)


@pytest.mark.parametrize("yaw_rate", [0.5, -0.5])
def test_turn_command_gives_rate_and_sign(sim: Simulation, yaw_rate: float) -> None:
    sim.command(0.0, yaw_rate)
    sim.run_for(1.0)
    assert sim.twist()[1] == pytest.approx(yaw_rate, abs=0.02)
    assert math.copysign(1.0, sim.pose().yaw) == math.copysign(1.0, yaw_rate)


def test_scan_sees_the_box_at_its_distance(sim: Simulation) -> None:
    sim.sense()
    ranges = sim.scan()
    assert len(ranges) == 360
    assert ranges[0] == pytest.approx(BOX_FACE_X - LIDAR_X, abs=0.02)
    assert math.isinf(ranges[90])  # nothing to the left within 3.5 m


def test_driving_into_the_box_stops_the_robot(sim: Simulation) -> None:
    sim.command(0.2, 0.0)
    sim.run_for(14.0)  # 2.33 m to the box at 0.2 m/s, then pushing against it
    front_x = sim.pose().x + 0.069  # chassis front edge in base_link
    assert front_x == pytest.approx(BOX_FACE_X, abs=0.01)
    assert abs(sim.twist()[0]) < 0.02
    assert sim.warnings() == {}


def test_reset_returns_to_the_start_pose_and_keeps_time() -> None:
    sim = Simulation(SimulationSettings(start_pose=StartPose(0.5, -0.2, 90.0)))
    assert sim.pose().yaw == pytest.approx(math.pi / 2)
    sim.command(0.2, 0.5)
    sim.run_for(1.0)
    sim.reset()
    assert sim.time == pytest.approx(1.0)
    assert (sim.pose().x, sim.pose().y) == pytest.approx((0.5, -0.2))
    assert sim.command_twist == (0.0, 0.0)


def test_a_robot_at_rest_only_sees_time_pass(sim: Simulation) -> None:
    stepped = Simulation()
    for world in (sim, stepped):
        world.run_for(1.0)  # settled on its wheels
    assert sim.at_rest()
    for _ in range(100):
        sim.advance(10)
        stepped.step(10)
    assert sim.still and sim.time == stepped.time  # the same sum of timesteps
    assert abs(sim.data.qpos - stepped.data.qpos).max() < 1e-8  # the physics would not move it
    sim.command(0.2, 0.0)
    sim.advance(250)
    assert not sim.still and sim.twist()[0] > 0.1  # a command makes it step again


def test_a_reset_robot_settles_before_it_rests(sim: Simulation) -> None:
    sim.reset()
    assert not sim.at_rest()  # placed above the floor: it falls onto its wheels first
    sim.advance(10)
    assert not sim.still


def test_imu_feels_gravity_and_the_turn(sim: Simulation) -> None:
    sim.command(0.0, 0.5)
    sim.run_for(1.0)
    sim.sense()
    reading = sim.imu()
    assert reading.linear_acceleration[2] == pytest.approx(9.81, abs=0.1)
    assert reading.angular_velocity[2] == pytest.approx(0.5, abs=0.02)
