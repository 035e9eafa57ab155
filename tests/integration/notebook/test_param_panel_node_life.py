"""Lesson 11's parameter panel follows its node's life (issue 59): gone, it says so with how to
start it again and refuses changes and saves; back, it reads every value from the node again.
Real nodes started and stopped through the lessons' own doors (`lesson.run`, the take-over
another lesson's `%ros2 run` does)."""

from __future__ import annotations

import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml

from course_lib.config.course import load_course_settings
from course_lib.core.errors import CourseError
from course_lib.core.waiting import wait_until
from course_lib.lab.takeover import take_over
from course_lib.lessons import Lesson
from course_lib.notebook.widgets import EventsTable, NodeNotRunningError, ParameterPanel
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import get_session

pytestmark = [pytest.mark.ros, pytest.mark.slow]

NODE = "/descriptor_vel_node"
RUN = ("parameter_descriptors", "descriptor_vel", "--ros-args", "-p", "use_sim_time:=true")
COMMAND = "%ros2 run parameter_descriptors descriptor_vel --ros-args -p use_sim_time:=true"
# Seen gone within a graph look-up or two after a clean stop (LOOK_S 0.5 s); a busy host's
# discovery may take a few seconds more.
GONE_WITHIN_S = 10.0


@pytest.fixture
def lesson() -> Iterator[Lesson]:
    session = get_session()  # the panel and the `ros2` API talk through the process's session
    course_lesson = Lesson(11, session, load_course_settings())
    yield course_lesson
    for child in course_lesson.started.values():
        child.stop()
    session.close()


def _logged(panel: ParameterPanel) -> str:
    return "".join(output.get("text", "") for output in panel.log.outputs)


def _changeable(panel: ParameterPanel) -> list[str]:
    """Return the names of the controls a learner can change (read-only ones never)."""
    return [name for name, control in panel.controls.items() if not control.disabled]


def _stop_and_check_refusals(panel: ParameterPanel, path: Path) -> None:
    """Stop the node as another lesson's `%ros2 run` does; check what the panel says and
    refuses while it is gone."""
    assert take_over("descriptor_vel"), "the node was not the lessons' to stop"
    assert wait_until(lambda: panel.save_button.disabled, GONE_WITHIN_S), "never seen gone"
    status = panel.status.value
    assert f"{NODE} is not running (stopped at " in status, status
    assert f"start it again with <code>{COMMAND}</code>" in status, status
    assert _changeable(panel) == []
    started = time.monotonic()
    with pytest.raises(NodeNotRunningError) as refused:
        panel.save()
    assert time.monotonic() - started < 1.0, "a save of a gone node waited for it"
    assert isinstance(refused.value, CourseError)
    assert f"{NODE} is not running" in str(refused.value) and COMMAND in str(refused.value)
    assert not path.exists()
    panel.save_button.click()  # a click that was on its way as the button was disabled
    assert "Not saved: " in _logged(panel) and "is not running" in _logged(panel)
    assert panel.set("velocity", 0.1) is False
    panel.controls["travel_time"].value = 2.5  # what moving the slider does
    assert panel.controls["travel_time"].value == 1.5, "a value not set stays on the slider"
    assert _logged(panel).count(f"Not set (velocity 0.1): {NODE} is not running") == 1


def test_the_panel_says_its_node_stopped_and_reads_it_again_when_back(
    lesson: Lesson, tmp_path: Path
) -> None:
    lesson.run(*RUN)
    path = tmp_path / "panel_params.yaml"
    panel = ParameterPanel(NODE, save_path=path, session=lesson.session)
    try:
        assert panel.set("travel_time", 1.5) and panel.set("velocity", 0.24)
        _stop_and_check_refusals(panel, path)

        lesson.run(*RUN, "-p", "travel_time:=2.0")  # back, with values of its own
        assert wait_until(lambda: not panel.save_button.disabled, 20.0), panel.status.value
        assert "is running again" in panel.status.value
        values = {name: control.value for name, control in panel.controls.items()}
        assert values == {"velocity": 0.0, "travel_time": 2.0, "max_travel": 1.5}
        assert sorted(_changeable(panel)) == ["travel_time", "velocity"]
        time.sleep(1.0)  # the changes refused while it was gone never reach the node later
        assert api.param_get(NODE, "velocity").value == 0.0
        assert api.param_get(NODE, "travel_time").value == 2.0
        saved = yaml.safe_load(panel.save().read_text())[NODE]["ros__parameters"]
        assert saved == {"max_travel": 1.5, "travel_time": 2.0, "velocity": 0.0}

        assert take_over("descriptor_vel")  # the line names how it was started last
        assert wait_until(lambda: panel.save_button.disabled, GONE_WITHIN_S)
        assert f"{COMMAND} -p travel_time:=2.0</code>" in panel.status.value
    finally:
        panel.close()


def test_a_closed_panel_stops_its_look_ups_and_its_listening(
    lesson: Lesson, tmp_path: Path
) -> None:
    lesson.run(*RUN)
    node = lesson.session.node
    timers = set(node.timers)
    panel = ParameterPanel(NODE, save_path=tmp_path / "p.yaml", session=lesson.session)
    witness = None
    try:
        (look_up,) = set(node.timers) - timers  # one timer follows the node's life
        assert look_up.timer_period_ns >= 200_000_000, "more than a few look-ups a second"
        panel.close()
        assert set(node.timers) == timers, "the closed panel's timer still runs"
        witness = EventsTable(lesson.session)  # hears each event after the panel would
        assert api.param_set(NODE, "travel_time", 3.0).successful
        assert wait_until(lambda: any(c.value == 3.0 for c in witness.changes), 10.0)
        assert panel.controls["travel_time"].value == 0.0, "the closed panel still listens"
    finally:
        panel.close()
        if witness is not None:
            witness.close()


def test_sliders_give_each_step_a_pixel_and_read_out_to_the_step(
    lesson: Lesson, tmp_path: Path
) -> None:
    """travel_time's 300 steps had a 94 px track (a 300 px slider) and a readout of 1.50."""
    lesson.run(*RUN)
    panel = ParameterPanel(NODE, save_path=tmp_path / "p.yaml", session=lesson.session)
    panel.close()
    travel, velocity = panel.controls["travel_time"], panel.controls["velocity"]
    assert travel.readout_format == ".1f" and velocity.readout_format == ".2f"
    for slider, steps in ((travel, 300), (velocity, 26)):
        width = int(str(slider.layout.width).removesuffix("px"))
        # the label (110 px) and the readout with the margins (~100 px) beside the track
        assert width - 210 >= steps, f"{slider.description}: {width} px for {steps} steps"
        assert width <= 900 and slider.layout.max_width == "100%"
