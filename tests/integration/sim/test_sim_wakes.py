"""A world wakes for what is read, not for every point of its streams (sim.ros.bridge._doze).

A wake of the physics loop costs the world about 0.5 ms of CPU here, whatever it does: a
driving world that woke for each of its 50 points a second spent a third of its CPU on that.
Nobody reads /odom or /clock at their rate in a lesson; the course's own readers take samples
in batches of 0.1 s, and a watched 3D view gets a frame every 40 ms. A ROS reader of a stream
still gets each message when it is due.
"""

from __future__ import annotations

import itertools
import os
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from course_lib.core.waiting import wait_until
from course_lib.notebook import World, start_world
from course_lib.session.session import Session
from course_lib.sim.world.samples import SAMPLES_TOPIC, batch_size, unpack

pytestmark = [pytest.mark.ros, pytest.mark.sim]

ODOM_PERIOD_S = 0.02  # config/simulation.yaml's 50 Hz, which the world here runs with


@pytest.fixture(scope="module")
def world(session: Session) -> Iterator[World]:
    started = start_world(session, show=False)
    yield started
    started.stop()


def _loop_switches(world: World) -> int:
    """Return how many times the world's physics loop (its main thread) has slept so far."""
    pid = world.process.pid
    for line in Path(f"/proc/{pid}/task/{pid}/status").read_text().splitlines():
        if line.startswith("voluntary_ctxt_switches:"):
            return int(line.split()[1])
    raise AssertionError("no voluntary_ctxt_switches in /proc")


def _driving(world: World) -> None:
    world.drive(0.2, 0.3)  # a circle: it never reaches the box
    wait_until(lambda: world.odom().linear_mps > 0.15, 10.0, message="the robot did not drive")


def test_a_driving_world_nobody_reads_wakes_for_its_samples_only(
    session: Session, world: World
) -> None:
    from std_msgs.msg import Float64MultiArray

    heard: list[tuple[float, list[Any]]] = []
    sub = session.node.create_subscription(
        Float64MultiArray, SAMPLES_TOPIC, lambda m: heard.append((time.monotonic(), m.data)), 50
    )
    try:
        _driving(world)
        time.sleep(0.5)
        before, start = _loop_switches(world), time.monotonic()
        time.sleep(3.0)
        rate = (_loop_switches(world) - before) / (time.monotonic() - start)
        came = [(t, unpack(data)) for t, data in heard if t >= start]
    finally:
        session.node.destroy_subscription(sub)
    assert rate < 30, f"the loop slept {rate:.0f} times a second (50 points a second)"
    stamps = [s.time_s for _, rows in came for s in rows]
    gaps = {round(b - a, 6) for a, b in itertools.pairwise(stamps)}
    assert gaps == {ODOM_PERIOD_S}, f"samples lost or doubled: steps {sorted(gaps)}"
    sizes = {len(rows) for _, rows in came}
    assert sizes == {batch_size(1 / ODOM_PERIOD_S)}, f"messages of {sizes} samples (0.1 s each)"


def test_a_reader_of_odom_gets_each_message_when_it_is_due(session: Session, world: World) -> None:
    from nav_msgs.msg import Odometry

    arrivals: list[float] = []
    sub = session.node.create_subscription(
        Odometry, "/odom", lambda _m: arrivals.append(time.monotonic()), 50
    )
    try:
        _driving(world)
        wait_until(lambda: len(arrivals) > 10, 10.0, message="no /odom came")
        start = time.monotonic()
        time.sleep(2.0)
        came = [t for t in arrivals if t >= start]
    finally:
        session.node.destroy_subscription(sub)
    assert len(came) >= 50, f"{len(came)} /odom messages in 2 s (50 Hz)"
    spacing = sorted(b - a for a, b in itertools.pairwise(came))
    assert spacing[len(spacing) // 2] > 0.01, f"/odom came in bursts: spacing {spacing[:10]}"


def test_every_thread_of_the_world_is_background_work(world: World) -> None:
    # The worlds' wake-ups never preempt a learner's command (course_lib.core.host.scheduling);
    # on a learner's own computer (this test's) they keep their usual weight, and the
    # learner's own processes stay as they were.
    from course_lib.core.host.scheduling import is_background_work

    pid = world.process.pid
    threads = [int(tid) for tid in os.listdir(f"/proc/{pid}/task")]
    assert len(threads) > 5  # the loop, the ROS executors, Fast DDS's, the view's
    assert [tid for tid in threads if not is_background_work(tid, nice=0)] == []
    assert not is_background_work(os.getpid())
