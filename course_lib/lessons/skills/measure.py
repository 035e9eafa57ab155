"""What the skill exercises measure: the robot on /odom, the node's log lines, other nodes.

Everything comes from the real thing: /odom readings recorded from the moment an exercise is
armed (with the wall time they arrived, to line them up with a node's log lines), the lines the
learner's node printed (param_vel_node logs its velocity on every 0.1 s tick), and the
parameters of the nodes running now. What the node's files give it is `file_values`.
"""

from __future__ import annotations

import itertools
import logging
import math
import re
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Any

from ...core.errors import CourseError

_log = logging.getLogger(__name__)

__all__ = [
    "MOVING_MPS",
    "OdomTrace",
    "distance_m",
    "first_tick",
    "node_holding",
    "steady_odom",
]

# what a parameter read or write raises when the node is gone or does not answer
PARAM_ERRORS = (CourseError, RuntimeError, TimeoutError)

_STEADY_S = 0.2  # simulated seconds between the readings compared
_SPEED_TOLERANCE = 0.002  # m/s
_TICK = re.compile(r"Velocity parameter is: (-?[0-9.]+)")
MOVING_MPS = 0.01  # m/s: a robot slower than this stands still
_RECENT = 30000  # /odom readings kept in full: 10 minutes at 50 Hz
_ARCHIVED = 20000  # older ones, thinned: over 5 hours of a steady robot
_ARCHIVE_EVERY_S = 1.0  # simulated s: a steady robot's older readings, one a second


def distance_m(a: Any, b: Any) -> float:
    """Return the straight-line distance between two poses (x, y in m)."""
    return math.hypot(b.x - a.x, b.y - a.y)


def _steady(world: Any, *, still_wait_s: float = 1.0) -> Any:
    """Return the first /odom reading after the robot's speed stopped changing.

    A speed change set just before (the node acts on its next 0.1 s tick) is let through
    first, so the window that follows measures the drive, not the start; a robot standing
    still gets `still_wait_s` of simulated time to start moving.
    """
    first = previous = world.odom()
    while True:
        reading = world.wait_sim_time(previous.time_s + _STEADY_S)
        steady = abs(reading.linear_mps - previous.linear_mps) < _SPEED_TOLERANCE
        moving = abs(reading.linear_mps) >= _SPEED_TOLERANCE
        waited = reading.time_s - first.time_s
        if (steady and (moving or waited >= still_wait_s)) or waited >= max(5.0, still_wait_s):
            return reading
        previous = reading


def steady_odom(world: Any, *, still_wait_s: float = 1.0) -> Any:
    """Return the first /odom reading after the robot's speed stopped changing (a robot
    standing still gets `still_wait_s` of simulated time to start moving)."""
    return _steady(world, still_wait_s=still_wait_s)


class OdomTrace:
    """Every /odom reading since `attach`, with the wall time it arrived.

    The last 10 minutes in full; older readings thinned to each change of speed and one a
    simulated second (hours of them): a learner who reads for an hour between starting a node
    and running the check is judged on the node's first seconds all the same.
    """

    def __init__(self) -> None:
        self.readings: deque[tuple[float, Any]] = deque(maxlen=_RECENT)
        self.archive: deque[tuple[float, Any]] = deque(maxlen=_ARCHIVED)
        self._world: Any = None
        self._received = 0  # readings appended since attach, those dropped off the deque too
        self._cond = threading.Condition()

    def _on(self, reading: Any) -> None:
        with self._cond:
            if len(self.readings) == self.readings.maxlen:
                self._archive(self.readings[0])  # about to drop off the full record
            self.readings.append((time.time(), reading))
            self._received += 1
            self._cond.notify_all()

    def _archive(self, item: tuple[float, Any]) -> None:
        """Keep an old reading if the speed changed since the last one kept, or a second passed."""
        if self.archive:
            last = self.archive[-1][1]
            reading = item[1]
            same = abs(reading.linear_mps - last.linear_mps) < _SPEED_TOLERANCE
            if same and reading.time_s - last.time_s < _ARCHIVE_EVERY_S:
                return
        self.archive.append(item)

    def attach(self, world: Any) -> None:
        """Record `world`'s /odom from now on (once: a second attach moves the recording)."""
        self.detach()
        with self._cond:
            self.readings.clear()
            self.archive.clear()
            self._received = 0
        self._world = world
        world.add_odom_listener(self._on)

    def detach(self) -> None:
        if self._world is not None:
            self._world.remove_odom_listener(self._on)
            self._world = None

    def first_moving(self, since: float, until: float) -> Any | None:
        """Return the first reading that arrived after wall time `since` with the robot
        moving; wait for one up to wall time `until` (None: the robot stood still)."""
        return self._wait_for(
            lambda wall_time, reading: (
                wall_time >= since and abs(reading.linear_mps) >= MOVING_MPS
            ),
            until,
        )

    def reading_after(self, wall: float, timeout: float) -> Any | None:
        """Return the first reading that arrived at or after wall time `wall` (waited for)."""
        return self._wait_for(lambda wall_time, _reading: wall_time >= wall, time.time() + timeout)

    def wait_sim_time(self, sim_s: float, timeout: float) -> None:
        """Wait until a reading of simulated time `sim_s` or later arrived (or `timeout` s)."""
        self._wait_for(lambda _wall, reading: reading.time_s >= sim_s, time.time() + timeout)

    def _wait_for(self, test: Callable[[float, Any], bool], until: float) -> Any | None:
        """Return the first reading that `test(wall time it arrived, reading)` passes; wait
        for one up to wall time `until`; None if none came."""
        seen = 0  # readings tested so far, counted since attach (the oldest drop off the deque)
        with self._cond:
            older = list(self.archive)  # tested first, once: the record before the full one
            while True:
                fresh = min(self._received - seen, len(self.readings))  # the newest, untested
                newest_first = itertools.islice(reversed(self.readings), fresh)
                for wall_time, reading in [*older, *reversed(list(newest_first))]:
                    if test(wall_time, reading):
                        return reading
                older = []
                seen = self._received
                left = until - time.time()
                if left <= 0:
                    return None
                self._cond.wait(min(left, 0.2))

    def speed(self, start_s: float, end_s: float) -> float:
        """Return the mean forward speed between simulated times `start_s` and `end_s` (m/s).

        Where the thinned record has fewer than two readings inside, the last one before the
        window counts too (the speed held until the next one kept), if the record covers it.
        """
        with self._cond:
            every = [r for _wall, r in itertools.chain(self.archive, self.readings)]
        inside = [r for r in every if start_s <= r.time_s <= end_s]
        before = [r for r in every if r.time_s < start_s][-1:]
        if len(inside) < 2:
            covered = any(r.time_s >= end_s for r in every)
            inside = [*before, *inside] if before and covered else []
        if not inside:
            return 0.0
        return sum(r.linear_mps for r in inside) / len(inside)


def first_tick(lines: list[Any]) -> tuple[float, float] | None:
    """Return (wall time, velocity) of param_vel_node's first logged tick, or None."""
    for line in lines:
        found = _TICK.search(line.text)
        if found:
            return line.time, float(found.group(1))
    return None


def node_holding(target: float, graded: str, tolerance: float) -> tuple[str, float]:
    """Return another running node whose `velocity` is `target` (the right value, wrong node)."""
    from ...ros2.api import nodes_and_params as api

    for name in api.node_list():
        if name == graded:
            continue
        try:
            value = api.param_get(name, "velocity").value
        except PARAM_ERRORS:  # no such parameter, or the node just left
            continue
        if isinstance(value, float) and abs(value - target) <= tolerance:
            return name, value
    return "", 0.0
