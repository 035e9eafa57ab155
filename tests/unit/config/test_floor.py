"""What the robot meets driving straight on from any pose, in the shipped world (pure)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from course_lib.config.floor import (
    FLOOR_EDGE,
    FLOOR_HALF_M,
    blocker,
    free_ahead,
    obstacle_words,
)
from course_lib.config.simulation import Obstacle, SimulationSettings, load_simulation_settings
from course_lib.lessons.skills.room import room_needed_m

SCENE = Path(__file__).resolve().parents[3] / "course_lib/models/turtlebot3_waffle_pi/scene.xml"


@pytest.fixture(scope="module")
def world() -> SimulationSettings:
    return load_simulation_settings()


def test_the_red_box_is_met_2_25_m_ahead_of_the_start(world: SimulationSettings) -> None:
    ahead = free_ahead(world, 0.0, 0.0, 0.0, limit=5.0)
    assert (ahead.free_m, ahead.blocker) == (2.25, "obstacle_box")


def test_a_robot_against_the_box_has_no_room(world: SimulationSettings) -> None:
    ahead = free_ahead(world, 2.26, 0.0, 0.0, limit=1.0)
    assert (ahead.free_m, ahead.blocker) == (0.0, "obstacle_box")


def test_room_short_of_the_limit_is_free(world: SimulationSettings) -> None:
    assert free_ahead(world, 0.0, 0.0, 0.0, limit=1.0).blocker is None


def test_backwards_the_floor_ends(world: SimulationSettings) -> None:
    ahead = free_ahead(world, 0.0, 0.0, 0.0, limit=6.0, backwards=True)
    assert ahead.blocker == FLOOR_EDGE
    assert ahead.free_m == pytest.approx(FLOOR_HALF_M - 0.25, abs=0.011)


def test_the_nearest_of_two_things_met_is_named() -> None:
    near = Obstacle("near", "cylinder", (1.0, 0.0), (0.2, 0.3))
    far = Obstacle("far", "box", (2.0, 0.0), (0.2, 1.0, 0.3))
    world = SimulationSettings(obstacles=(far, near))
    assert free_ahead(world, 0.0, 0.0, 0.0, limit=3.0).blocker == "near"


def test_turned_towards_the_wall(world: SimulationSettings) -> None:
    assert blocker(world, 0.0, 0.0, -math.pi / 2, 1.5) == "obstacle_wall"


def test_obstacles_are_named_in_a_persons_words(world: SimulationSettings) -> None:
    words = [obstacle_words(world, o.name) for o in world.obstacles]
    assert words == ["the red box", "the blue cylinder", "the grey wall"]
    red_box = Obstacle("red_box", "box", (3.0, 0.0), (0.2, 0.2, 0.2), color=(0.9, 0.1, 0.1))
    assert obstacle_words(SimulationSettings(obstacles=(red_box,)), "red_box") == "the red box"


def test_the_floor_size_is_the_scenes() -> None:
    assert f'type="plane" size="{FLOOR_HALF_M:g} {FLOOR_HALF_M:g}' in SCENE.read_text()


def test_a_drive_needs_its_window_and_the_settling_at_the_top_speed_at_most() -> None:
    assert room_needed_m(0.2, 3.0) == pytest.approx(0.2 * 4.5 + 0.05)
    assert room_needed_m(5.0, 3.0) == room_needed_m(0.26, 3.0)
    assert room_needed_m(-0.2, 3.0) == room_needed_m(0.2, 3.0)
