"""The start-up exercises of lessons 9, 10 and 11: a node started after arming must hold a
parameter's target value from its first second (from an edited dump, a launch file of the
learner's, or the panel's saved file)."""

from __future__ import annotations

import contextlib
import os
from pathlib import Path
from typing import Any

from . import file_values, measure
from .exercise_base import DESCRIPTOR_VEL, SkillExercise
from .judge import StartupAttempt, StartupTask, Verdict, judge_startup
from .measure import PARAM_ERRORS

__all__ = ["LaunchExercise", "ParamsFileExercise", "SavedPanelExercise"]

_START_WAIT_S = 10.0  # after the checker sets velocity, at most, until the robot moves
# after a node's first tick, at most, until the simulation hears it (a new participant's
# first announcement missed waits for the next one; 0.86 s seen on a busy host, 3 s possible)
_HEARD_WITHIN_S = 3.0


class _StartupExercise(SkillExercise):
    """A node started after arming must hold `param` at the target from its first second."""

    needs_file = True
    param = "velocity"
    unit = "m/s"
    first_line = "Velocity parameter is"  # what the node logs first

    @property
    def settings(self) -> Any:
        return self.lesson.settings.startup_exercises

    @property
    def target(self) -> float:
        raise NotImplementedError

    @property
    def tolerance(self) -> float:
        return self.settings.tolerance_mps

    def how(self) -> str:
        raise NotImplementedError

    def _started(self) -> tuple[Any, list[Any], Path | None]:
        """Return the newest process started since arming, its output lines, its file."""
        fresh = [c for c in self._children() if c.pid not in self._known]
        if not fresh:
            return None, [], None
        child = fresh[-1]
        return child, child.lines, file_values.params_file_of(child.argv, Path(os.getcwd()))

    def _file_value(self, path: Path) -> file_values.FileValue:
        return file_values.params_file_value(path, self.node)

    def measuring(self) -> str:
        """Return the line said before the measurement's wait."""
        return (
            f"Measuring the robot's speed on /odom in {self.node}'s first "
            f"{self.settings.window_s:g} s of simulated time ..."
        )

    def _start_time(self, lines: list[Any]) -> tuple[float | None, float | None]:
        """Return (wall time of the node's first tick, its logged value), if it logged one."""
        tick = measure.first_tick(lines)
        return (tick[0], tick[1]) if tick else (None, None)

    def _measure(self, t0: float, first: float) -> tuple[float, float, str]:
        """Return (value measured at the start, value now, the sentence) from /odom.

        The window is `window_s` simulated seconds after the robot began to move (a node that
        starts at a speed: on a busy host the simulation may hear its first command seconds
        after its first tick), else after the node's first tick (`t0`, wall time).
        """
        window = self.settings.window_s
        began = None
        if abs(first) >= measure.MOVING_MPS:  # since a second before: its line came late
            began = self.trace.first_moving(t0 - 1.0, until=t0 + window + _HEARD_WITHIN_S)
        if began is None:
            began = self.trace.reading_after(t0, timeout=window + 5.0)
        start = 0.0
        if began is not None:  # else no /odom at all: the robot did not drive
            end = began.time_s + window + 0.5
            self.trace.wait_sim_time(end, timeout=2 * (window + 0.5) + 5.0)
            start = self.trace.speed(end - 1.0, end)
        now = self.lesson.current_world.odom().linear_mps
        return start, now, f"the robot drove at {start:.2f} m/s in the node's first seconds"

    def _judge(self, number: int) -> Verdict:
        child, _lines, path = self._started()
        task = StartupTask(
            self.node,
            self.executable,
            self.param,
            self.unit,
            self.target,
            self.tolerance,
            self.how(),
            self.needs_file,
        )
        show = self.lesson.settings.show_hints
        if child is None:
            return judge_startup(StartupAttempt(False), task, number=number, show_hints=show)
        # a node started moments ago: its first line (or its crash) first
        child.wait_for_line(lambda line: self.first_line in line.text, 5.0)
        found = self._file_value(path) if path is not None else file_values.FileValue()
        t0, first = self._start_time(child.lines)
        if t0 is None or not child.alive:  # it ended at start-up: say why, if its file says
            crashed = "InvalidParameterType" in child.text()
            problem = found.problem or ("integer" if crashed else "")
            attempt = StartupAttempt(
                True, str(path or ""), problem, found.written or "1", found.key,
                measured_text=f"{self.node} ended at start-up",
            )  # fmt: skip
            return judge_startup(attempt, task, number=number, show_hints=show)
        first_value = found.value if first is None and found.value is not None else first or 0.0
        print(self.measuring(), flush=True)
        start, now, text = self._measure(t0, first_value)
        elsewhere, other = "", 0.0
        if abs(start - self.target) > self.tolerance:
            elsewhere, other = measure.node_holding(self.target, self.node, self.tolerance)
        attempt = StartupAttempt(
            True,
            str(path or ""),
            found.problem,
            found.written,
            found.key,
            first_value,
            start,
            now,
            text,
            elsewhere,
            other,
        )
        return judge_startup(attempt, task, number=number, show_hints=show)


class ParamsFileExercise(_StartupExercise):
    """Lesson 9: dump, edit, restart with --params-file: the new speed from the first second."""

    name = "09 params file"

    @property
    def target(self) -> float:
        return self.settings.params_file_mps

    def how(self) -> str:
        return (
            '`lesson.stop("param_vel")`, then `%ros2 run parameter_tests param_vel --ros-args '
            "--params-file my_files/<your edited dump>.yaml`."
        )

    def task(self) -> str:
        return (
            f"Task: make {self.node} start at velocity {self.target:g}: dump its parameters to "
            "a file, edit it, restart the node with `--params-file`; then run the check. The "
            "robot must drive at the new speed from the node's first second."
        )


class LaunchExercise(_StartupExercise):
    """Lesson 10: a launch file of the learner's starts param_vel_node at a given velocity."""

    name = "10 launch file"
    needs_file = False

    @property
    def target(self) -> float:
        return self.settings.launch_mps

    def how(self) -> str:
        return (
            "write a Node(package='parameter_tests', executable='param_vel', "
            "name='param_vel_node', parameters=[...]) launch file with `%%writefile "
            "my_files/<name>.launch.py`, then "
            '`run = lesson.launch("my_files/<name>.launch.py")`.'
        )

    def task(self) -> str:
        return (
            f"Task: write a launch file that starts {self.node} with velocity {self.target:g}, "
            "launch it with `lesson.launch(...)`, then run the check."
        )

    def _children(self) -> list[Any]:
        return [h.child for h in self.lesson.state.get("launches", [])]

    def _started(self) -> tuple[Any, list[Any], Path | None]:
        from ...launch.command.resolve import LaunchCommandError, resolve_launch_file

        fresh = [h for h in self.lesson.state.get("launches", []) if h.pid not in self._known]
        if not fresh:
            return None, [], None
        handle = fresh[-1]
        rest = handle.argv[1:]
        file = rest.pop(0) if rest and ":=" not in rest[0] else None
        try:
            path, _args = resolve_launch_file(handle.argv[0], file, rest)
        except LaunchCommandError:  # no such package or file: the launch itself said so
            return handle.child, handle.child.lines, None
        return handle.child, handle.child.lines, Path(path)

    def _file_value(self, path: Path) -> file_values.FileValue:
        return file_values.launch_file_value(path, self.executable)


class SavedPanelExercise(_StartupExercise):
    """Lesson 11: travel_time set with the panel and saved survives a restart of the node."""

    name = "11 saved panel"
    executable = "descriptor_vel"
    node = DESCRIPTOR_VEL
    param = "travel_time"
    unit = "s"
    first_line = "Ready:"

    @property
    def target(self) -> float:
        return self.settings.saved_panel_travel_s

    @property
    def tolerance(self) -> float:
        return self.settings.travel_tolerance_s

    def how(self) -> str:
        return (
            '`lesson.stop("descriptor_vel")`, then `%ros2 run parameter_descriptors '
            "descriptor_vel --ros-args -p use_sim_time:=true --params-file "
            "my_files/panel_params.yaml`."
        )

    def task(self) -> str:
        v = self.lesson.settings.default_velocity_mps
        return (
            f"Task: set travel_time to {self.target:.1f} with the panel and save; restart "
            f"{self.node} so that it keeps it; then run the check: it sets velocity {v:g} and "
            "measures the trip."
        )

    def measuring(self) -> str:
        v = self.lesson.settings.default_velocity_mps
        return (
            f"Setting velocity {v:g} on {self.node} and measuring its trip on /odom (until the "
            "robot stops) ..."
        )

    def _start_time(self, lines: list[Any]) -> tuple[float | None, float | None]:
        ready = next((ln for ln in lines if self.first_line in ln.text), None)
        return (ready.time, None) if ready else (None, None)

    def _file_value(self, path: Path) -> file_values.FileValue:
        return file_values.params_file_value(path, self.node, self.param)

    def _measure(self, t0: float, first: float) -> tuple[float, float, str]:
        """Start a trip at the course's velocity; the trip's length in time is measured."""
        from ...ros2.api import nodes_and_params as api

        v = self.lesson.settings.default_velocity_mps
        world = self.lesson.current_world
        # the node's sim clock needs its first /clock message before a trip can be timed
        self.trace.reading_after(t0 + self.settings.window_s, timeout=self.settings.window_s + 5)
        try:
            now = float(api.param_get(self.node, self.param).value)
        except PARAM_ERRORS:
            now = 0.0
        start_pose = world.odom().pose
        if not api.param_set(self.node, "velocity", v).successful:
            return 0.0, now, "the node refused the checker's velocity"
        limit = max(self.target * 2, self.target + 3.0)
        try:
            moving = world.wait_for_odom(lambda r: abs(r.linear_mps) > 0.01, _START_WAIT_S)
        except TimeoutError:  # a verdict, not a traceback: the learner's node drove nothing
            return 0.0, now, f"the robot did not move within {_START_WAIT_S:g} s of velocity {v:g}"
        with contextlib.suppress(TimeoutError):
            world.wait_for_odom(
                lambda r: abs(r.linear_mps) < 0.003 or r.time_s > moving.time_s + limit, 60.0
            )
        end = world.odom()
        still = abs(end.linear_mps) < 0.003
        driven = measure.distance_m(start_pose, end.pose)
        trip = driven / v if still else 0.0
        text = (
            f"its trip at {v:g} m/s was {driven:.2f} m, {trip:.2f} s"
            if still
            else f"the robot did not stop by itself ({driven:.2f} m at {v:g} m/s)"
        )
        return trip, now, text
