"""The lessons' tools against real nodes and the real simulation: exercise, panel, self-check."""

from __future__ import annotations

import os
import signal
import time
from collections.abc import Iterator

import pytest
import yaml

from course_lib.config.course import load_course_settings
from course_lib.core.waiting import wait_until
from course_lib.lessons import Lesson
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import get_session

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

NODE = "/descriptor_vel_node"


@pytest.fixture(scope="module")
def lesson() -> Iterator[Lesson]:
    session = get_session()  # the `ros2` Python API talks through the process's session
    course_lesson = Lesson(11, session, load_course_settings())
    course_lesson.world(show=False)
    node = session.run(
        "parameter_descriptors", "descriptor_vel", "--ros-args", "-p", "use_sim_time:=true"
    )
    assert node.wait_for_line("Ready", 10.0) is not None
    yield course_lesson
    course_lesson.current_world.stop()
    node.stop()
    session.close()


def test_exercise_judges_a_real_motion(lesson: Lesson) -> None:
    from course_lib.lessons.exercise import TravelExercise

    travel = TravelExercise(lesson)
    travel.arm()
    assert api.param_set(NODE, "travel_time", 2.0).successful
    assert api.param_set(NODE, "velocity", 0.2).successful
    miss = travel.check()
    assert not miss.passed and "short of" in miss.message and miss.hint
    assert api.param_set(NODE, "travel_time", 5.0).successful
    assert api.param_set(NODE, "velocity", 0.2).successful
    hit = travel.check()
    assert hit.passed, hit.message


def test_panel_follows_the_node_and_saves_valid_yaml(lesson: Lesson, tmp_path) -> None:
    from course_lib.notebook.widgets import ParameterPanel

    panel = ParameterPanel(NODE, save_path=tmp_path / "saved.yaml", session=lesson.session)
    try:
        velocity = panel.controls["velocity"]
        assert (velocity.min, velocity.max, velocity.step) == (0.0, 0.26, 0.01)
        assert panel.controls["max_travel"].disabled
        assert api.param_set(NODE, "travel_time", 10.0).successful  # set elsewhere: synced
        lesson.current_world.wait_for_odom(lambda _r: panel.controls["travel_time"].value == 10.0)
        assert not panel.set("velocity", 0.2)  # 2.0 m: the on-set callback refuses it
        assert panel.commands[-1] == "ros2 param set /descriptor_vel_node velocity 0.2"
        assert velocity.value == 0.0, "a refused value is not left on the slider"
    finally:
        panel.close()
    path = panel.save()
    data = yaml.safe_load(path.read_text())
    assert data[NODE]["ros__parameters"]["travel_time"] == 10.0
    assert api.param_set(NODE, "travel_time", 0.0).successful


def test_a_wait_for_odom_says_whether_readings_came(lesson: Lesson) -> None:
    """A wait that times out tells a condition never met from a simulation that sent nothing
    (a paused one here): the two call for different searches."""
    world = lesson.current_world
    with pytest.raises(TimeoutError, match=r"\(\d+ readings came, none matched\)"):
        world.wait_for_odom(lambda _reading: False, timeout=0.5)
    os.kill(world.process.pid, signal.SIGSTOP)
    try:
        # readings sent just before the pause are still on their way: let them arrive first
        last = [time.monotonic()]

        def arrived(_reading: object) -> None:
            last[0] = time.monotonic()

        world.add_odom_listener(arrived)
        assert wait_until(lambda: time.monotonic() - last[0] > 0.3, 5), "readings kept coming"
        world.remove_odom_listener(arrived)
        with pytest.raises(TimeoutError, match="the simulation runs but sent no reading"):
            world.wait_for_odom(lambda _reading: False, timeout=0.5)
    finally:
        os.kill(world.process.pid, signal.SIGCONT)
    assert world.wait_for_odom(timeout=10.0)
