"""Lesson 7 at a person's pace: the learner sets velocity, reads, and only then runs the cell
that measures. Meanwhile the robot drives on into the red box 2.25 m ahead of its start; the
measurement still judges what the learner did, and says what happened to the robot.

The world runs at 4 times real time, so 'reading' for 12 simulated seconds takes 3 s here.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from course_lib.config.course import load_course_settings
from course_lib.lessons import Lesson
from course_lib.lessons.catalogue import run_checks
from course_lib.notebook import start_world
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import get_session

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

NODE = "/param_vel_node"
DROVE_AT = "the robot drove at 0.2 m/s (measured on /odom)"


@pytest.fixture(scope="module")
def lesson(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Lesson]:
    session = get_session()
    start_world(session, show=False, real_time_factor=4.0)
    seven = Lesson(7, session, load_course_settings())
    seven.learner_dir = tmp_path_factory.mktemp("my_files")  # the attempts file goes here
    seven.world(show=False)
    node = session.run("parameter_tests", "param_vel")  # as the `%ros2 run` cell starts it
    assert node.wait_for_line(lambda line: "Velocity" in line.text, 10.0) is not None
    yield seven
    api.param_set(NODE, "velocity", 0.0)
    seven.current_world.stop()
    seven.stop_nodes()
    session.close()


def _read_until_the_robot_meets_the_box(lesson: Lesson, velocity: float) -> None:
    """Set velocity as the lesson says, then 'read' until the robot stands against the box."""
    assert api.param_set(NODE, "velocity", velocity).successful
    lesson.current_world.wait_for_odom(
        lambda r: r.pose.x > 2.0 and abs(r.linear_mps) < 0.01, timeout=30.0
    )


def test_drive_for_after_reading_measures_the_drive_and_names_the_box(
    lesson: Lesson, capsys: pytest.CaptureFixture[str]
) -> None:
    _read_until_the_robot_meets_the_box(lesson, 0.2)
    capsys.readouterr()
    report = repr(lesson.drive_for(3.0))
    said = capsys.readouterr().out
    assert "stood against the red box" in said and "back at its start pose" in said, said
    assert "Measuring 3 s of simulated time on /odom ..." in said
    assert "/odom says 0.20 m/s; the robot drove 0.6 m" in report, report
    verdicts = {c.what: c.passed for c in run_checks(lesson)}
    assert verdicts[DROVE_AT], verdicts
    assert api.param_set(NODE, "velocity", 0.0).successful


def test_a_drive_longer_than_the_floor_says_what_stopped_it(lesson: Lesson) -> None:
    lesson.current_world.reset()
    assert api.param_set(NODE, "velocity", 0.2).successful
    report = repr(lesson.drive_for(15.0))
    assert "It stands against the red box" in report, report
    assert api.param_set(NODE, "velocity", 0.0).successful


def test_the_drive_exercise_passes_the_right_answer_checked_after_reading(
    lesson: Lesson, capsys: pytest.CaptureFixture[str]
) -> None:
    from course_lib.lessons.skills.exercises import DriveExercise

    drive = DriveExercise(lesson)
    drive.arm()
    _read_until_the_robot_meets_the_box(lesson, 0.15)
    capsys.readouterr()
    verdict = drive.check()
    said = capsys.readouterr().out
    assert verdict.passed, verdict
    assert "stood against the red box" in said, said
