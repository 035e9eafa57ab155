"""`lesson.history`, `lesson.reset` and `lesson.diff` against the real param_vel node over DDS.

Each door the course offers sets `velocity` for real (the `%ros2` magic, the terminal's `ros2`
through its daemon, the parameter panel), another node sets it with plain rclpy, and the node
is started with a params file and by a launch file: the history must name each source.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path

import pytest
from param_setter import another_node_sets_velocity

from course_lib.config.course import load_course_settings
from course_lib.core.param_journal import journal_path
from course_lib.core.paths import REPO_ROOT
from course_lib.core.waiting import wait_until
from course_lib.lessons import Lesson
from course_lib.notebook.magics import run_line
from course_lib.notebook.widgets.events import parameter_events
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import Session, get_session

pytestmark = [pytest.mark.ros, pytest.mark.slow]

NODE = "/param_vel_node"


@pytest.fixture(scope="module")
def lesson() -> Iterator[Lesson]:
    session = get_session()  # `%ros2` and the Python API talk through the process's session
    parameter_events(session)  # as `start(N)` does: listening before any node starts
    journal_path(session.domain_id).unlink(missing_ok=True)  # a domain used before: not ours
    yield Lesson(8, session, load_course_settings())
    _terminal(session, "daemon stop")
    session.close()


def _terminal(session: Session, command: str) -> str:
    """Run a command through the course's terminal `ros2` (its daemon for param verbs)."""
    env = {**session.env, "PYTHONPATH": str(REPO_ROOT), "COLUMNS": "80"}
    proc = subprocess.run(
        [sys.executable, "-m", "course_lib.ros2.command.cli", *command.split()],
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    return proc.stdout + proc.stderr


def _other_node_sets(session: Session, value: float) -> None:
    """Set velocity from another node: plain rclpy, no door of the course."""
    another_node_sets_velocity(session.env, value)


def _start_node(*args: str) -> None:
    line = " ".join(["run parameter_tests param_vel", *args])
    assert "Velocity parameter is" in run_line(line).output.text
    assert wait_until(lambda: NODE in api.node_list(), 10.0)


def _entries_settle(lesson: Lesson, count: int) -> list:
    """Return the history once it holds `count` entries (events travel over DDS)."""
    wait_until(lambda: len(lesson.history().entries) >= count, 10.0)
    return list(lesson.history().entries)


def test_history_names_each_door_and_reset_restores(lesson: Lesson, tmp_path: Path) -> None:
    params = tmp_path / "start.yaml"
    params.write_text("param_vel_node:\n  ros__parameters:\n    velocity: 0.05\n")
    _start_node("--ros-args", "--params-file", str(params))
    assert api.param_get(NODE, "velocity").value == 0.05

    assert run_line("param set /param_vel_node velocity 0.1").output.text == (
        "Set parameter successful\n"
    )
    assert _terminal(lesson.session, "param set /param_vel_node velocity 0.15") == (
        "Set parameter successful\n"
    )
    panel = lesson.parameter_panel(NODE, save_as=str(tmp_path / "panel.yaml"))
    try:
        assert panel.set("velocity", 0.2)
    finally:
        panel.close()
    _other_node_sets(lesson.session, 0.25)
    assert not api.param_set(NODE, "velocity", 1).successful  # refused: no entry

    entries = _entries_settle(lesson, 5)
    got = [(e.name, e.old and e.old.value, e.new and e.new.value, e.source) for e in entries]
    assert got == [
        ("velocity", None, 0.05, "params file start.yaml"),
        ("velocity", 0.05, 0.1, "%ros2 magic"),
        ("velocity", 0.1, 0.15, "terminal ros2"),
        ("velocity", 0.15, 0.2, "parameter panel"),
        ("velocity", 0.2, 0.25, "the node itself or another node"),
    ]
    text = repr(lesson.history())
    assert "#2  velocity  0.05 → 0.1" in text and "%ros2 magic" in text
    assert "<td>parameter panel</td>" in lesson.history()._repr_html_()

    assert repr(lesson.diff()) == textwrap.dedent("""\
        --- start-up values
        +++ /param_vel_node (running)
         /param_vel_node:
           ros__parameters:
             start_type_description_service: true
             use_sim_time: false
        -    velocity: 0.05
        +    velocity: 0.25
        """)
    assert repr(lesson.reset()) == (
        "Reset /param_vel_node to its start-up values:\n  velocity: 0.25 → 0.05\n"
    )
    assert api.param_get(NODE, "velocity").value == 0.05
    assert repr(lesson.reset()) == (
        "Nothing to reset: /param_vel_node runs with its start-up values.\n"
    )
    assert lesson.diff().same
    last = _entries_settle(lesson, 6)[-1]
    assert (last.new.value, last.source) == (0.05, "lesson.reset")


def test_diff_against_a_params_file(lesson: Lesson, tmp_path: Path) -> None:
    _start_node()
    dump = tmp_path / "dump.yaml"
    dump.write_text(_terminal(lesson.session, "param dump /param_vel_node"))
    assert lesson.diff(path=dump).same
    assert run_line("param set /param_vel_node velocity 0.2").output.exit_code == 0
    assert repr(lesson.diff(path=dump)).splitlines()[-2:] == [
        "-    velocity: 0.0",
        "+    velocity: 0.2",
    ]
    assert repr(lesson.diff(path=dump)).startswith(f"--- {dump}\n+++ /param_vel_node (running)")
    assert run_line(f"param load /param_vel_node {dump}").output.exit_code == 0
    assert lesson.diff(path=dump).same
    last = _entries_settle(lesson, 2)[-1]
    assert (last.new.value, last.source) == (0.0, "params file dump.yaml (%ros2 magic)")


def test_a_restarted_node_starts_a_new_history(lesson: Lesson) -> None:
    _start_node("--ros-args", "-p", "velocity:=0.07")
    history = lesson.history()
    assert [(e.new.value, e.source) for e in history.entries] == [
        (0.07, "-p at start (%ros2 magic)")
    ]
    assert run_line("param set /param_vel_node velocity 0.1").output.exit_code == 0
    _entries_settle(lesson, 2)
    assert "Velocity parameter is" in lesson.run("parameter_tests", "param_vel").lines[-1]
    assert lesson.history().entries == ()


def test_launch_file_overrides_and_terminal_reset(lesson: Lesson, tmp_path: Path) -> None:
    from course_lib.launch import launch

    params = tmp_path / "vel.yaml"
    params.write_text("/**:\n  ros__parameters:\n    velocity: 0.03\n")
    file = tmp_path / "vel.launch.py"
    file.write_text(
        textwrap.dedent(f"""\
        from launch import LaunchDescription
        from launch_ros.actions import Node

        def generate_launch_description():
            return LaunchDescription([Node(
                package='parameter_tests', executable='param_vel', name='param_vel_node',
                parameters=[{{'velocity': 0.02}}, {str(params)!r}])])
        """)
    )
    run_line("run parameter_tests param_vel")  # the lesson's node: the launch's replaces it
    lesson.stop_nodes()
    handle = launch(str(file), session=lesson.session)
    try:
        assert handle.wait_for(r"Velocity parameter is", timeout=15.0) is not None
        assert wait_until(lambda: api.param_get(NODE, "velocity").value == 0.03, 10.0)
        sources = [(e.new.value, e.source) for e in lesson.history().entries]
        assert sources == [
            (0.02, "launch file vel.launch.py"),
            (0.03, "params file vel.yaml (launch file vel.launch.py)"),
        ]
        assert _terminal(lesson.session, "param set /param_vel_node velocity 0.3") == (
            "Set parameter successful\n"
        )
        assert repr(lesson.reset()).endswith("  velocity: 0.3 → 0.03\n")
    finally:
        handle.stop()


def test_speed_plot_marks_are_numbered_like_the_history(lesson: Lesson) -> None:
    from std_msgs.msg import Float64MultiArray

    from course_lib.notebook.widgets import SpeedPlot
    from course_lib.sim.world.samples import FIELDS, SAMPLES_TOPIC

    _start_node()
    plot = SpeedPlot(lesson.session)
    # no world here: one sample gives the plot the simulated time its marks are placed at
    samples = lesson.session.node.create_publisher(Float64MultiArray, SAMPLES_TOPIC, 10)
    try:
        assert run_line("param set /param_vel_node velocity 0.12").output.exit_code == 0
        assert wait_until(lambda: samples.get_subscription_count() > 0, 10.0)
        samples.publish(Float64MultiArray(data=[1.0] * len(FIELDS)))
        assert wait_until(lambda: plot.marks, 10.0)
        (entry,) = lesson.history().entries
        assert (entry.number, entry.source) == (1, "%ros2 magic")
        assert [label for _t, label in plot.marks] == ["#1 velocity := 0.12"]
    finally:
        plot.close()
        lesson.session.node.destroy_publisher(samples)


def test_reset_restores_after_each_door(lesson: Lesson, tmp_path: Path) -> None:
    from course_lib.core.errors import CourseError

    _start_node("--ros-args", "-p", "velocity:=0.05")
    panel = lesson.parameter_panel(NODE, save_as=str(tmp_path / "panel.yaml"))
    doors = {
        "%ros2 magic": lambda: run_line("param set /param_vel_node velocity 0.2"),
        "terminal ros2": lambda: _terminal(
            lesson.session, "param set /param_vel_node velocity 0.2"
        ),
        "parameter panel": lambda: panel.set("velocity", 0.2),
        "another node": lambda: _other_node_sets(lesson.session, 0.2),
    }
    try:
        for door, set_it in doors.items():
            set_it()
            assert wait_until(lambda: api.param_get(NODE, "velocity").value == 0.2, 5.0), door
            assert repr(lesson.reset()).endswith("velocity: 0.2 → 0.05\n"), door
            assert api.param_get(NODE, "velocity").value == 0.05, door
    finally:
        panel.close()
    bad = tmp_path / "bad.yaml"
    bad.write_text("velocity: [\n")
    with pytest.raises(CourseError, match="is not a params file for /param_vel_node"):
        lesson.diff(path=bad)


def test_a_node_the_terminal_runs_has_its_params_file_traced(
    lesson: Lesson, tmp_path: Path
) -> None:
    _start_node()  # a lesson ran this executable once: its node's name is known
    lesson.stop_nodes()
    params = tmp_path / "terminal.yaml"
    params.write_text("/**:\n  ros__parameters:\n    velocity: 0.06\n")
    env = {**lesson.session.env, "PYTHONPATH": str(REPO_ROOT)}
    command = ["run", "parameter_tests", "param_vel", "--ros-args", "--params-file"]
    proc = subprocess.Popen(
        [sys.executable, "-m", "course_lib.ros2.command.cli", *command, str(params)],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,  # Ctrl-C in a terminal reaches its whole process group
    )
    try:
        assert wait_until(lambda: NODE in api.node_list(), 15.0)
        assert _terminal(lesson.session, "param set /param_vel_node velocity 0.2") == (
            "Set parameter successful\n"
        )
        history = _entries_settle(lesson, 2)
        assert [(e.new.value, e.source) for e in history] == [
            (0.06, "params file terminal.yaml"),
            (0.2, "terminal ros2"),
        ]
        assert lesson.history().start_door == "terminal ros2"
    finally:
        os.killpg(proc.pid, signal.SIGINT)
        proc.wait(15)
