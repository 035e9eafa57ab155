"""Lesson 11's exercise, checked from the robot's actual motion on /odom (simulated time).

Arming stops the robot (velocity 0.0), puts it back at its start pose and watches every /odom
reading from then on: a learner may set the parameters and read for a minute before running
the check, and the trip is judged all the same. The watch stops the robot as soon as it passes
the target plus the tolerance (the attempt failed for sure), so a trip that never ends stays on
the free floor at any pace. Arming keeps the node's travel_time: it is the learner's value, and
resetting it to 0.0 (no limit) would turn a refused `travel_time 5` into a trip with no end.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import threading
import time
from collections.abc import Callable
from typing import Any, ClassVar

from ..config.trip import Trip, answer_trip
from ..core.errors import CourseError
from ..core.param_journal import acting_door
from .catalogue.shared import only_driver, other_drivers
from .files import Text
from .judging import NODE, Held, TravelAttempt, Verdict, holds_text, judge_travel, replay
from .skills.attempts import AttemptLog
from .skills.measure import PARAM_ERRORS
from .skills.requests import learner_requests

__all__ = ["TravelExercise", "TripWatch"]

NAME = "11 travel"  # in the attempt log and on the progress page
DOOR = "travel exercise"  # the history's name for the checker's own requests
MOVED_M = 0.02  # farther than this from the start: the robot moved
MOVING_MPS = 0.003  # slower than this: the robot stands still
REST_S = 0.3  # simulated seconds standing still that end a trip
START_GRACE_S = 3.0  # simulated seconds the check gives a robot that has not moved yet
START_GRACE_WALL_S = 2.0  # ... and wall seconds at least (a world faster than real time)


class TripWatch:
    """The robot's trip since arming, from every /odom reading; stops it past `limit_m`."""

    def __init__(
        self, world: Any, limit_m: float, stop: Callable[[], None], *, at_arm: Held
    ) -> None:
        self.world, self.limit_m, self._stop = world, limit_m, stop
        self.at_arm, self.armed_wall = at_arm, time.time()  # what the node held, and when
        self.start = self.latest = world.odom()
        self.farthest_m = self.top_mps = 0.0
        self.moving_s: float | None = None  # simulated time of the last reading that moved
        self.passed = False
        self._cond = threading.Condition()
        self._wake = threading.Event()  # passed, or closed: the guard acts (or leaves)
        self._closed = False
        world.add_odom_listener(self._on)
        threading.Thread(target=self._guard, name="travel-guard", daemon=True).start()

    def distance_m(self) -> float:
        """Return how far the robot stands from where the trip began (m)."""
        a, b = self.start.pose, self.latest.pose
        return math.hypot(b.x - a.x, b.y - a.y)

    def _on(self, reading: Any) -> None:
        with self._cond:
            self.latest = reading
            distance = self.distance_m()
            self.farthest_m = max(self.farthest_m, distance)
            self.top_mps = max(self.top_mps, abs(reading.linear_mps))
            if abs(reading.linear_mps) >= MOVING_MPS:
                self.moving_s = reading.time_s
            if distance > self.limit_m and not self.passed:
                self.passed = True
                self._wake.set()
            self._cond.notify_all()

    def _guard(self) -> None:
        self._wake.wait()
        if not self._closed:
            with contextlib.suppress(*PARAM_ERRORS):  # the node is gone: nothing drives
                self._stop()

    @property
    def moved(self) -> bool:
        """Return True if the robot went farther than MOVED_M from its start."""
        return self.farthest_m > MOVED_M

    def at_rest(self) -> bool:
        """Return True once the robot has stood still for REST_S of simulated time."""
        since = self.moving_s if self.moving_s is not None else self.start.time_s
        return self.latest.time_s - since >= REST_S

    def wait(self, done: Callable[[], bool], timeout: float) -> bool:
        """Wait until `done()` (called with the watch's lock held) or `timeout` wall seconds."""
        deadline = time.monotonic() + timeout
        with self._cond:
            while not done():
                left = deadline - time.monotonic()
                if left <= 0:
                    return False
                self._cond.wait(min(left, 0.5))
        return True

    def close(self) -> None:
        """Stop watching (the guard thread ends)."""
        self.world.remove_odom_listener(self._on)
        self._closed = True
        self._wake.set()


class TravelExercise:
    """'Travel target_m and stop, with parameters only': arm, let the learner act, check."""

    _watch: ClassVar[TripWatch | None] = None  # one armed trip per kernel, whichever instance

    def __init__(self, lesson: Any) -> None:
        self.lesson = lesson
        self.settings = lesson.settings.travel_exercise
        self.attempts: list[Verdict] = []
        self.log = AttemptLog(lesson.learner_dir)  # counts go on after a kernel restart

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
        """Stop the robot, put it back at its start pose and watch its next trip."""
        held = self._rearm()
        return Text(
            f"Robot at its start pose; {holds_text(held)}. Task: travel "
            f"{self.settings.target_m:.2f} m (± {self.settings.tolerance_m * 100:g} cm) and "
            "stop, using parameters only."
        )

    def close(self) -> None:
        """Stop watching the robot (a later `arm()` watches again)."""
        watch, TravelExercise._watch = TravelExercise._watch, None
        if watch is not None:
            watch.close()

    def _rearm(self) -> Held:
        """Stop the robot, reset the world, watch from the start pose; return what the node
        holds (its travel_time is the learner's: kept)."""
        self.close()
        self._stop_robot(strict=True)
        world = self.lesson.current_world
        world.reset()
        held = self._held_now()
        limit = self.settings.target_m + self.settings.tolerance_m
        TravelExercise._watch = TripWatch(world, limit, self._stop_at_once, at_arm=held)
        return held

    def _stop_robot(self, *, strict: bool = False) -> None:
        """Set velocity 0.0 on the node, if it holds another value (each set shows on plots)."""
        from ..ros2.api import nodes_and_params as api

        with acting_door(DOOR):
            if api.param_get(NODE, "velocity").value == 0.0:
                return
        result = self._stop_at_once()
        if strict and not result.successful:
            raise CourseError(f"Could not stop {NODE}: {result.reason}")

    def _stop_at_once(self) -> Any:
        """Set velocity 0.0 without asking first (the guard's stop: the robot is moving past
        its limit, and every round trip saved is road it does not drive); return the result."""
        from ..ros2.api import nodes_and_params as api

        with acting_door(DOOR):
            return api.param_set(NODE, "velocity", 0.0)

    def _held_now(self) -> Held:
        from ..ros2.api import nodes_and_params as api

        try:
            velocity = api.param_get(NODE, "velocity").value
            travel_time = api.param_get(NODE, "travel_time").value
        except PARAM_ERRORS:
            return Held()
        return Held(float(velocity), float(travel_time))

    def _wait_until_certain(self, watch: TripWatch, bound_s: float) -> bool:
        """Wait until the trip's outcome is certain, at most `bound_s` simulated seconds;
        return True if the robot came to rest by itself."""
        print(
            "Measuring the trip on /odom until the robot stops (at most "
            f"{bound_s:g} s of simulated time) ...",
            flush=True,
        )
        # The world's time now, not the watch's last reading: a resting robot's readings come
        # a second of simulated time to a message, and a stale start would cut the grace short.
        begin = max(watch.latest.time_s, watch.world.odom().time_s)
        wall_begin = time.monotonic()

        def certain() -> bool:
            now = watch.latest.time_s
            if now >= begin + bound_s:
                return True
            if watch.moved:
                return watch.at_rest()
            # a world faster than real time on a busy host: the node's first command may take
            # longer than the grace in simulated time to reach it, so wait a wall floor too
            waited_wall = time.monotonic() - wall_begin >= START_GRACE_WALL_S
            return now >= begin + START_GRACE_S and waited_wall

        watch.wait(certain, timeout=3 * bound_s + 30.0)
        return watch.moved and watch.at_rest() and not watch.passed

    def _measure(self, watch: TripWatch) -> TravelAttempt:
        """Measure the trip, stop the robot whatever the outcome, say what the node held."""
        bound = self.settings.timeout_s
        now = self._held_now()  # before the check stops anything
        stopped = self._wait_until_certain(watch, bound)
        with contextlib.suppress(*PARAM_ERRORS):
            self._stop_robot()
        watch.wait(watch.at_rest, timeout=5.0)  # where the check's stop left it
        requests = learner_requests(
            self.lesson.session.domain_id, watch.armed_wall, NODE, checker=DOOR
        )
        trip, refusals = replay(requests, watch.at_arm)
        measured = round(watch.top_mps, 2) if watch.moved else 0.0  # a door with no journal
        velocity = trip.velocity or now.velocity or measured
        travel_time = now.travel_time if now.travel_time is not None else trip.travel_time
        return TravelAttempt(
            watch.moved,
            stopped,
            watch.distance_m(),
            watch.limit_m if watch.passed else 0.0,
            bound if watch.moved and not stopped and not watch.passed else 0.0,
            Held(velocity, travel_time),
            refusals,
        )

    def check(self) -> Verdict:
        """Judge the robot's motion since `arm()`, then re-arm for the next attempt."""
        watch = TravelExercise._watch
        if watch is None:
            raise CourseError("The exercise is not armed.", hint="run `travel.arm()` first.")
        attempt = self._measure(watch)
        others = other_drivers(self.lesson, "descriptor_vel")
        number = self.log.tally(NAME).attempts + 1
        if others:  # not only the learner's answer moved the robot: no verdict on it
            self._rearm()
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
        tally = self.log.add(NAME, verdict.passed)
        if tally.unsaved:  # the verdict still shows, with the one line saying so
            verdict = dataclasses.replace(verdict, note=tally.unsaved)
        self.attempts.append(verdict)
        from .progress.client import report_attempt

        report_attempt(self.lesson.number, NAME, number, verdict.passed)
        self.lesson.state["exercise_passed"] = any(v.passed for v in self.attempts)
        held = self._rearm()
        if verdict.passed:
            return verdict
        then = f"Next attempt: the robot is back at its start pose; {holds_text(held)}."
        return dataclasses.replace(verdict, then=then)
