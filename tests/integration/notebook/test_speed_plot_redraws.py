"""Lesson 7's live speed plot redraws only after new /odom samples that show motion (a still
robot's samples do not), at most once per REFRESH_S: a plot of a quiet world costs its kernel
nothing (issue 23: one redraw takes ~0.1 s of CPU)."""

from __future__ import annotations

import time
from collections.abc import Iterator

import pytest
from std_msgs.msg import Float64MultiArray

from course_lib.notebook.widgets import SpeedPlot
from course_lib.notebook.widgets.speed_plot import REFRESH_S
from course_lib.session.session import Session
from course_lib.sim.world.samples import FIELDS, SAMPLES_TOPIC

pytestmark = pytest.mark.ros


@pytest.fixture
def session() -> Iterator[Session]:
    own = Session()
    yield own
    own.close()


def _odom(stamp_s: float, speed: float, count: int = 1) -> Float64MultiArray:
    """`count` /odom samples 0.02 s apart from `stamp_s`, as the simulation sends them to the
    course's readers (5 to a message at 50 Hz)."""
    data: list[float] = []
    for i in range(count):
        row = dict.fromkeys(FIELDS, 0.0) | {
            "time_s": stamp_s + i * 0.02,
            "qw": 1.0,
            "linear_mps": speed,
        }
        data += row.values()
    return Float64MultiArray(data=data)


def _wait(predicate, timeout: float) -> bool:  # type: ignore[no-untyped-def]
    deadline = time.monotonic() + timeout
    while not predicate() and time.monotonic() < deadline:
        time.sleep(0.05)
    return bool(predicate())


def _count_drawings(plot: SpeedPlot) -> list[int]:
    """Count the plot's drawings (each redraw draws the whole picture once)."""
    count = [0]
    draw = plot.svg

    def counted() -> str:
        count[0] += 1
        return draw()

    plot.svg = counted  # type: ignore[method-assign]
    return count


def test_the_live_plot_redraws_only_after_new_samples(session: Session) -> None:
    plot = SpeedPlot(session)
    drawn = _count_drawings(plot)
    publisher = session.node.create_publisher(Float64MultiArray, SAMPLES_TOPIC, 10)
    try:
        plot.show()
        drawn[0] = 0  # show() draws the first picture itself
        time.sleep(3.0)  # no /odom at all: nothing to redraw
        assert drawn[0] == 0, f"{drawn[0]} redraws of a plot that got no sample"
        assert _wait(lambda: publisher.get_subscription_count() > 0, 10.0)
        publisher.publish(_odom(1.0, 0.1))
        assert _wait(lambda: drawn[0] >= 1, 10.0), "a new sample was never drawn"
        assert _wait(lambda: len(plot.samples) == 1, 5.0)
        time.sleep(2 * REFRESH_S + 0.5)
        quiet = drawn[0]
        time.sleep(3.0)  # no new sample again
        assert drawn[0] == quiet, "the plot redrew without new samples"
        started = time.monotonic()
        for i in range(20):  # a busy /odom: 50 samples a second for 2 s
            publisher.publish(_odom(2.0 + i * 0.1, 0.2, count=5))
            time.sleep(0.1)
        elapsed = time.monotonic() - started
        assert _wait(lambda: len(plot.samples) == 101, 5.0)
        busy = drawn[0] - quiet
        assert 1 <= busy <= elapsed / REFRESH_S + 2, f"{busy} redraws in {elapsed:.1f} s"
        time.sleep(2 * REFRESH_S + 0.5)
        moving = drawn[0]
        for i in range(20):  # the robot stopped: samples keep coming, all at speed 0
            publisher.publish(_odom(4.0 + i * 0.1, 0.0, count=5))
            time.sleep(0.1)
        assert _wait(lambda: len(plot.samples) == 201, 5.0)
        time.sleep(2 * REFRESH_S + 0.5)
        assert drawn[0] - moving <= 1, "a still robot's samples redrew the plot"
    finally:
        plot.close()
        session.node.destroy_publisher(publisher)


def test_a_change_heard_before_any_sample_is_marked_at_the_first_one(session: Session) -> None:
    """A velocity set right after the plot appears, before its /odom subscription got a sample,
    is marked where the samples start (it was marked at 0 s, outside a run at 500 s: the saved
    replay lost it)."""
    from rcl_interfaces.msg import Parameter, ParameterEvent, ParameterType

    plot = SpeedPlot(session)
    odom = session.node.create_publisher(Float64MultiArray, SAMPLES_TOPIC, 10)
    events = session.node.create_publisher(ParameterEvent, "/parameter_events", 10)
    try:
        assert _wait(lambda: events.get_subscription_count() > 0, 10.0)
        change = Parameter(name="velocity")
        change.value.type = ParameterType.PARAMETER_DOUBLE
        change.value.double_value = 0.2
        events.publish(ParameterEvent(node="/param_vel_node", changed_parameters=[change]))
        assert _wait(lambda: plot._unplaced, 5.0), "the change was never heard"
        assert plot.marks == []
        assert _wait(lambda: odom.get_subscription_count() > 0, 10.0)
        odom.publish(_odom(500.0, 0.0))
        assert _wait(lambda: plot.marks, 5.0)
        assert [(t, label.split(" ", 1)[-1]) for t, label in plot.marks] == [
            (500.0, "velocity := 0.2")
        ]
    finally:
        plot.close()
        session.node.destroy_publisher(odom)
        session.node.destroy_publisher(events)
