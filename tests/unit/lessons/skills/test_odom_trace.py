"""The skill exercises' record of /odom: readings found by simulated time, however late or
bunched they arrived, and new ones still seen once the record is full."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import pytest

from course_lib.lessons.skills.measure import OdomTrace
from course_lib.notebook.world import OdomReading
from course_lib.sim.world.kinematics import Pose2D


class ListenedWorld:
    """A world that hands the readings it is given to its /odom listeners (pure)."""

    def __init__(self) -> None:
        self.listeners: list[Callable[[OdomReading], None]] = []

    def add_odom_listener(self, listener: Callable[[OdomReading], None]) -> None:
        self.listeners.append(listener)

    def remove_odom_listener(self, listener: Callable[[OdomReading], None]) -> None:
        self.listeners.remove(listener)

    def send(self, time_s: float, speed: float) -> None:
        for listener in self.listeners:
            listener(OdomReading(time_s, Pose2D(0.0, 0.0, 0.0), speed, 0.0))


def _trace() -> tuple[OdomTrace, ListenedWorld]:
    world, trace = ListenedWorld(), OdomTrace()
    trace.attach(world)
    return trace, world


def test_a_full_record_still_sees_the_readings_that_come_next() -> None:
    trace, world = _trace()
    for step in range(trace.readings.maxlen + 10):  # standing still for over 10 minutes
        world.send(step * 0.02, 0.0)
    later = threading.Timer(0.2, world.send, (999.0, 0.18))
    later.start()
    moving = trace.first_moving(since=0.0, until=time.time() + 5.0)
    later.join()
    assert moving is not None and moving.time_s == 999.0


def test_a_robot_that_stands_still_is_waited_for_until_the_limit() -> None:
    trace, world = _trace()
    world.send(0.0, 0.0)
    started = time.monotonic()
    assert trace.first_moving(since=0.0, until=time.time() + 0.3) is None
    assert time.monotonic() - started >= 0.25


def test_the_speed_is_taken_over_simulated_time_however_the_readings_arrived() -> None:
    trace, world = _trace()
    for step in range(151):  # 3 s of /odom arriving at once: a busy process takes them late
        t = step * 0.02
        world.send(t, 0.18 if t >= 1.0 else 0.0)
    began = trace.first_moving(since=0.0, until=time.time())
    assert began is not None and began.time_s == pytest.approx(1.0)
    assert trace.speed(began.time_s + 0.5, began.time_s + 1.5) == pytest.approx(0.18)
    assert trace.speed(0.0, 0.9) == 0.0
    assert trace.speed(10.0, 11.0) == 0.0  # no reading: no speed


def test_a_node_started_fifteen_minutes_before_the_check_is_judged_on_its_first_seconds() -> None:
    trace, world = _trace()
    steps = 15 * 60 * 50  # 15 minutes of /odom at 50 Hz: the full record holds 10
    for step in range(steps):  # still for 1 s, 0.12 m/s from then on: the node's start
        t = step * 0.02
        world.send(t, 0.12 if t >= 1.0 else 0.0)
    began = trace.first_moving(since=0.0, until=time.time())
    assert began is not None and began.time_s == pytest.approx(1.0)
    assert trace.speed(began.time_s + 1.5, began.time_s + 2.5) == pytest.approx(0.12)
    assert len(trace.archive) < (steps - len(trace.readings)) / 10  # thinned, not all kept
