"""A robot at rest costs its lab little: its samples go out REST_BATCH_S to a message, and a
reader that needs a recent one gets it when it asks (sim.world.samples, notebook.world).

A learner reading a lesson leaves the robot still for minutes: the kernel woke ten times a
second for samples that all said the same (an idle lab's kernel 0.009 cores, the simulation's
loop 0.008). The world runs at real time here, as in a lab.
"""

from __future__ import annotations

import itertools
import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

from course_lib.core.waiting import wait_until
from course_lib.notebook import World, start_world
from course_lib.notebook.world import STALE_S
from course_lib.session.session import Session
from course_lib.sim.world.samples import (
    FRESH_HOLD_S,
    REST_BATCH_S,
    REST_S,
    SAMPLES_TOPIC,
    batch_size,
    unpack,
)

pytestmark = [pytest.mark.ros, pytest.mark.sim]

ODOM_HZ = 50.0  # config/simulation.yaml's rate, which the world here runs with
REST = batch_size(ODOM_HZ, REST_BATCH_S)
MOVING = batch_size(ODOM_HZ)


@pytest.fixture(scope="module")
def world(session: Session) -> Iterator[World]:
    started = start_world(session, show=False)
    yield started
    started.stop()


class Batches:
    """Every samples message this test hears: when it came (monotonic) and its samples."""

    def __init__(self, session: Session) -> None:
        from std_msgs.msg import Float64MultiArray

        self.heard: list[tuple[float, list[Any]]] = []
        self._lock = threading.Lock()
        self._session = session
        self._sub = session.node.create_subscription(
            Float64MultiArray, SAMPLES_TOPIC, self._on, 50
        )

    def _on(self, msg: Any) -> None:
        with self._lock:
            self.heard.append((time.monotonic(), unpack(msg.data)))

    def since(self, moment: float) -> list[tuple[float, list[Any]]]:
        with self._lock:
            return [(t, rows) for t, rows in self.heard if t >= moment]

    def close(self) -> None:
        self._session.node.destroy_subscription(self._sub)


@pytest.fixture
def batches(session: Session) -> Iterator[Batches]:
    heard = Batches(session)
    yield heard
    heard.close()


def _rested(world: World) -> None:
    """Stop and reset the robot, then let it rest past REST_S and one whole rest batch."""
    world.drive(0.0, 0.0)
    world.reset()
    time.sleep(REST_S + REST_BATCH_S + 0.5)


def test_a_resting_robot_sends_a_rest_batch_of_samples_to_a_message(
    world: World, batches: Batches
) -> None:
    _rested(world)
    start = time.monotonic()
    assert wait_until(lambda: len(batches.since(start)) >= 3, 10.0), batches.since(start)
    heard = batches.since(start)
    assert [len(rows) for _, rows in heard] == [REST] * len(heard)
    gaps = [b[0] - a[0] for a, b in itertools.pairwise(heard)]
    assert min(gaps) > 0.5 * REST_BATCH_S, gaps
    times = [s.time_s for _, rows in heard for s in rows]
    steps = {round(b * 1e9) - round(a * 1e9) for a, b in itertools.pairwise(times)}
    # every /odom point, none lost, each stamped to the nanosecond as /odom's would be (the
    # loop takes a rest batch's points in one pass, and the point after it one by one)
    assert steps == {round(1e9 / ODOM_HZ)}, steps


def test_a_reader_that_asks_gets_a_recent_reading_at_once(world: World, batches: Batches) -> None:
    """`World.odom()` on a resting robot: the samples that wait come at once, and the next
    ones a tenth of a second apart for FRESH_HOLD_S. Without the question (a reader that
    only takes its latest sample) the reading is up to REST_BATCH_S old."""
    _rested(world)
    # the world handle's latest sample is old: the rest batch came over STALE_S ago
    assert wait_until(lambda: time.monotonic() - batches.since(0.0)[-1][0] > STALE_S, 3.0)
    before = batches.since(0.0)[-1][1][-1].time_s
    asked = time.monotonic()
    reading = world.odom()
    took = time.monotonic() - asked
    assert took < 0.5, f"odom() took {took:.2f} s"
    assert reading.time_s > before, "no newer sample than the last rest batch's"
    time.sleep(FRESH_HOLD_S / 2)
    after = [len(rows) for _, rows in batches.since(asked)]
    assert after[1:] and set(after[1:]) == {MOVING}, after  # the held tenths of a second


def test_a_resting_world_keeps_real_time(world: World) -> None:
    """The loop sleeps through REST_BATCH_S of points at rest and takes them back to back:
    the simulated time slept through is not lost (the pacer's slack). Each reading may be up
    to STALE_S old when it is the answer (World.odom), so the bounds allow that at both ends;
    a lost doze would lose a third of the window or more."""
    _rested(world)
    window_s = 3 * REST_BATCH_S
    first, wall0 = world.odom().time_s, time.monotonic()
    time.sleep(window_s)
    last, wall1 = world.odom().time_s, time.monotonic()
    factor = (last - first) / (wall1 - wall0)
    slack = (2 * STALE_S + 0.05) / window_s
    assert 1 - slack < factor < 1 + slack, f"real-time factor {factor:.3f} over a rest"


def test_a_command_wakes_a_resting_robot_and_no_sample_is_lost(
    world: World, batches: Batches
) -> None:
    _rested(world)
    start = time.monotonic()
    world.drive(0.2, 0.0)
    try:
        moving = world.wait_for_odom(lambda r: r.linear_mps > 0.1, timeout=3.0)
        took = time.monotonic() - start
        assert took < 1.0, f"the robot moved {took:.2f} s after the command"
        time.sleep(0.5)
        heard = [s for _, rows in batches.since(start - REST_BATCH_S) for s in rows]
        times = [s.time_s for s in heard]
        steps = {round(b - a, 4) for a, b in itertools.pairwise(times)}
        assert steps == {round(1 / ODOM_HZ, 4)}, steps
        assert any(s.time_s >= moving.time_s for s in heard)
    finally:
        world.drive(0.0, 0.0)


def test_a_notebook_opened_on_a_resting_world_reads_it_at_once(
    session: Session, world: World
) -> None:
    """A notebook opened (or its kernel restarted) while the robot rests makes a new handle
    on the running world: its first reading comes when it asks, not after a rest batch (the
    samples the simulation only starts gathering once the new reader subscribes)."""
    _rested(world)
    world.detach()  # the first notebook's handle lets go; the world runs on, nobody reads
    time.sleep(1.0)  # the learner reads before opening the next notebook
    again = World(session, world.settings, world.process)
    try:
        asked = time.monotonic()
        again.odom()
        took = time.monotonic() - asked
        assert took < 0.6, f"the new handle's first reading took {took:.2f} s"
    finally:
        again.detach()
