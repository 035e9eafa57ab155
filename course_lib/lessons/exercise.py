"""Lesson 11's exercise, checked from the robot's actual motion on /odom (simulated time)."""

from __future__ import annotations

import contextlib
import math
from typing import Any

from ..config.trip import Trip, answer_trip
from ..core.errors import CourseError
from .checks import only_driver, other_drivers
from .files import Text
from .judging import TravelAttempt, Verdict, judge_travel
from .skills.attempts import AttemptLog

__all__ = ["TravelExercise"]

NODE = "/descriptor_vel_node"
NAME = "11 travel"  # in the attempt log and on the progress page


class TravelExercise:
    """'Travel target_m and stop, with parameters only': arm, let the learner act, check."""

    def __init__(self, lesson: Any) -> None:
        self.lesson = lesson
        self.settings = lesson.settings.travel_exercise
        self.attempts: list[Verdict] = []
        self.log = AttemptLog(lesson.learner_dir)  # counts go on after a kernel restart
        self._start: Any = None

    def answer(self) -> Trip:
        """Return one solution of the configured task (the lesson's stored answer)."""
        settings = self.lesson.settings
        trip = answer_trip(
            self.settings.target_m, self.settings.tolerance_m, settings.default_velocity_mps
        )
        if trip is None:
            raise CourseError(
                f"No velocity and travel_time reach {self.settings.target_m} m.",
                hint="run `make check-config`: it says which setting to change.",
            )
        return trip

    def arm(self) -> Text:
        """Stop the robot, put it back at its start pose and remember where it stands."""
        from ..ros2.api import nodes_and_params as api

        world = self.lesson.current_world
        for name in ("velocity", "travel_time"):
            result = api.param_set(NODE, name, 0.0)
            if not result.successful:
                raise CourseError(f"Could not reset {name}: {result.reason}")
        world.reset()
        self._start = world.odom()
        return Text(
            f"Robot at its start pose, {NODE} at rest. Task: travel "
            f"{self.settings.target_m:.2f} m (± {self.settings.tolerance_m * 100:g} cm) and stop, "
            "using parameters only."
        )

    def _measure(self) -> TravelAttempt:
        world = self.lesson.current_world
        start = self._start
        t0 = start.time_s

        def moved(r: Any) -> bool:
            return math.hypot(r.pose.x - start.pose.x, r.pose.y - start.pose.y) > 0.02

        with contextlib.suppress(TimeoutError):
            world.wait_for_odom(lambda r: moved(r) or r.time_s > t0 + 3.0, 30.0)
        now = world.odom()
        if not moved(now):
            return TravelAttempt(False, False, 0.0)
        limit = t0 + self.settings.timeout_s
        still_since: list[float] = []

        def at_rest(r: Any) -> bool:
            if abs(r.linear_mps) >= 0.003:
                still_since.clear()
                return r.time_s > limit
            still_since.append(r.time_s)
            return r.time_s - still_since[0] >= 0.3 or r.time_s > limit

        end = world.wait_for_odom(at_rest, self.settings.timeout_s * 3)
        stopped = abs(end.linear_mps) < 0.003
        dist = math.hypot(end.pose.x - start.pose.x, end.pose.y - start.pose.y)
        return TravelAttempt(True, stopped, dist)

    def check(self) -> Verdict:
        """Judge the robot's motion since `arm()`, then re-arm for the next attempt."""
        if self._start is None:
            raise CourseError("The exercise is not armed.", hint="run `travel.arm()` first.")
        attempt = self._measure()
        others = other_drivers(self.lesson, "descriptor_vel")
        number = self.log.tally(NAME).attempts + 1
        if others:  # not only the learner's answer moved the robot: no verdict on it
            self.arm()
            hint = only_driver(self.lesson, "descriptor_vel", NODE.lstrip("/"), others).hint
            return Verdict(False, f"Not judged (attempt {number} is still yours): {hint}")
        verdict = judge_travel(
            attempt,
            target_m=self.settings.target_m,
            tolerance_m=self.settings.tolerance_m,
            number=number,
            show_hints=self.lesson.settings.show_hints,
            answer=self.answer(),
        )
        self.log.add(NAME, verdict.passed)
        self.attempts.append(verdict)
        from .progress.client import report_attempt

        report_attempt(self.lesson.number, NAME, number, verdict.passed)
        self.lesson.state["exercise_passed"] = any(v.passed for v in self.attempts)
        self.arm()
        return verdict
