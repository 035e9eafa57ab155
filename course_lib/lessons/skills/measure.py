"""What the skill exercises measure: the robot on /odom, the node's log lines, its files.

Everything comes from the real thing: /odom readings recorded from the moment an exercise is
armed (with the wall time they arrived, to line them up with a node's log lines), the lines the
learner's node printed (param_vel_node logs its velocity on every 0.1 s tick), the command line
it was started with, the params or launch file it was given, and the parameters of the nodes
running now.
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
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from ...core.errors import CourseError

_log = logging.getLogger(__name__)

__all__ = [
    "MOVING_MPS",
    "FileValue",
    "OdomTrace",
    "distance_m",
    "first_tick",
    "launch_file_value",
    "node_holding",
    "params_file_of",
    "params_file_value",
    "steady_odom",
]

# what a parameter read or write raises when the node is gone or does not answer
PARAM_ERRORS = (CourseError, RuntimeError, TimeoutError)

_STEADY_S = 0.2  # simulated seconds between the readings compared
_SPEED_TOLERANCE = 0.002  # m/s
_TICK = re.compile(r"Velocity parameter is: (-?[0-9.]+)")
MOVING_MPS = 0.01  # m/s: a robot slower than this stands still


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
    """Every /odom reading since `attach`, with the wall time it arrived (about 10 minutes)."""

    def __init__(self) -> None:
        self.readings: deque[tuple[float, Any]] = deque(maxlen=30000)
        self._world: Any = None
        self._received = 0  # readings appended since attach, those dropped off the deque too
        self._cond = threading.Condition()

    def _on(self, reading: Any) -> None:
        with self._cond:
            self.readings.append((time.time(), reading))
            self._received += 1
            self._cond.notify_all()

    def attach(self, world: Any) -> None:
        """Record `world`'s /odom from now on (once: a second attach moves the recording)."""
        self.detach()
        with self._cond:
            self.readings.clear()
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
            while True:
                fresh = min(self._received - seen, len(self.readings))  # the newest, untested
                newest_first = itertools.islice(reversed(self.readings), fresh)
                for wall_time, reading in reversed(list(newest_first)):
                    if test(wall_time, reading):
                        return reading
                seen = self._received
                left = until - time.time()
                if left <= 0:
                    return None
                self._cond.wait(min(left, 0.2))

    def speed(self, start_s: float, end_s: float) -> float:
        """Return the mean forward speed between simulated times `start_s` and `end_s` (m/s)."""
        with self._cond:
            inside = [r for _wall, r in self.readings if start_s <= r.time_s <= end_s]
        if len(inside) < 2:
            return 0.0
        return sum(r.linear_mps for r in inside) / len(inside)


def first_tick(lines: list[Any]) -> tuple[float, float] | None:
    """Return (wall time, velocity) of param_vel_node's first logged tick, or None."""
    for line in lines:
        found = _TICK.search(line.text)
        if found:
            return line.time, float(found.group(1))
    return None


def params_file_of(argv: list[str], cwd: Path) -> Path | None:
    """Return the params file a node's command line passes (`--params-file FILE`), if any."""
    for flag, value in itertools.pairwise(argv):
        if flag == "--params-file":
            path = Path(value)
            return path if path.is_absolute() else cwd / path
    return None


@dataclass(frozen=True)
class FileValue:
    """What a file gives the node: its velocity, or why it gives none."""

    value: float | None = None
    problem: str = ""  # "", integer, wrong_key, no_parameter, missing_file, unreadable
    written: str = ""
    key: str = ""


def _typed(value: Any) -> FileValue:
    if value is None:
        return FileValue(problem="no_parameter")
    if isinstance(value, int) and not isinstance(value, bool):
        return FileValue(problem="integer", written=str(value))
    if isinstance(value, float):
        return FileValue(value=value)
    return FileValue(problem="integer", written=repr(value))  # a string, a list: no double


def params_file_value(path: Path, node: str, param: str = "velocity") -> FileValue:
    """Return the `param` a params file gives `node` (as rcl reads it: its key must match)."""
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        return FileValue(problem="missing_file")
    except (OSError, yaml.YAMLError):
        return FileValue(problem="unreadable")
    if not isinstance(data, dict) or not data:
        return FileValue(problem="wrong_key", key="(none)")
    names = {node, node.lstrip("/"), "/**", "**"}
    section = next((v for k, v in data.items() if k in names), None)
    if section is None:
        return FileValue(problem="wrong_key", key=str(next(iter(data))))
    params = section.get("ros__parameters", {}) if isinstance(section, dict) else {}
    return _typed(params.get(param) if isinstance(params, dict) else None)


def launch_file_value(path: Path, executable: str) -> FileValue:
    """Return the velocity a launch file gives `executable`'s node (read, not run)."""
    from ...launch.command.dry_run import dry_run

    try:
        report = dry_run(str(path))
    except Exception as error:  # the learner's own code: anything; the launch shows it too
        _log.info("launch file %s could not be planned: %r", path, error)
        return FileValue(problem="no_parameter")
    for plan in report.nodes:
        if Path(plan.cmd[0]).name == executable:
            found = plan.values.get("velocity")
            return _typed(found[0] if found else None)
    return FileValue(problem="no_parameter")


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
