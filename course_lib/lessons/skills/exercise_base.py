"""What every skill exercise does around its own measuring and judging.

Arm puts the robot back at its start pose and starts recording /odom; check measures what the
learner's node and the robot did since (each exercise its own way), judges it (`judge`), counts
the attempt in the learner's folder (`attempts`), tells the class's progress page on a hub,
stops the robot and arms again for the next attempt.
"""

from __future__ import annotations

import contextlib
import dataclasses
import time
from typing import Any

from ...core.errors import CourseError
from . import measure
from .attempts import AttemptLog
from .judge import Verdict
from .measure import PARAM_ERRORS

__all__ = ["DESCRIPTOR_VEL", "PARAM_VEL", "SkillExercise", "velocity_of"]

PARAM_VEL = "/param_vel_node"
DESCRIPTOR_VEL = "/descriptor_vel_node"


def velocity_of(node: str, missing: Any = 0.0) -> Any:
    """Return the velocity `node` holds now (`missing` if it does not answer)."""
    from ...ros2.api import nodes_and_params as api

    try:
        return api.param_get(node, "velocity").value
    except PARAM_ERRORS:
        return missing


def _set(node: str, name: str, value: float) -> None:
    from ...ros2.api import nodes_and_params as api

    with contextlib.suppress(*PARAM_ERRORS):  # the node may be gone: then nothing drives
        if node in api.node_list() and api.param_get(node, name).value != value:
            api.param_set(node, name, value)  # only a change: the speed plot marks each set


class SkillExercise:
    """What every skill exercise does around its own measuring and judging."""

    name = ""  # the attempt log's key and the progress page's column
    executable = "param_vel"
    node = PARAM_VEL

    def __init__(self, lesson: Any) -> None:
        self.lesson = lesson
        self.log = AttemptLog(lesson.learner_dir)
        self.trace = measure.OdomTrace()
        self.attempts: list[Verdict] = []
        self.armed_at: float | None = None
        self._known: set[int] = set()

    def task(self) -> str:
        raise NotImplementedError

    def _judge(self, number: int) -> Verdict:
        raise NotImplementedError

    def _stop_robot(self) -> None:
        _set(self.node, "velocity", 0.0)

    def _others(self) -> list[str]:
        """Return who else than the learner's node publishes on /cmd_vel (names, pids)."""
        from ...lab.drivers import describe
        from ...lab.drivers import other_drivers as others_of
        from ...ros2.api.nodes_and_params import client

        running = [c for c in self._children() if c.alive]
        own = running[-1].pid if running else None
        return [describe(p) for p in others_of(client(), own)]

    def _children(self) -> list[Any]:
        return [c for c in self.lesson.session.every_child if c.name == self.executable]

    def arm(self) -> str:
        """Stop the robot, put it back at its start pose, record /odom from now on."""
        world = self.lesson.current_world
        self._stop_robot()
        world.reset()
        self.trace.attach(world)
        self._known = {c.pid for c in self._children()}
        self.armed_at = time.time()
        tally = self.log.tally(self.name)
        done = f" (attempts so far: {tally.attempts})" if tally.attempts else ""
        return f"Robot at its start pose.{done} {self.task()}\n"

    def check(self) -> Verdict:
        """Judge what happened since `arm()`; count the attempt; arm again for the next one."""
        if self.armed_at is None:
            raise CourseError("The exercise is not armed.", hint="run its first cell again.")
        others = self._others()
        if others:  # not only the learner's node moved the robot: no verdict on it
            verb = "publish" if len(others) > 1 else "publishes"
            self.arm()
            number = self.log.tally(self.name).attempts + 1
            return Verdict(
                False,
                f"Not judged (attempt {number} is still yours): {', '.join(others)} also "
                f"{verb} on /cmd_vel: stop it (Ctrl-C in its terminal), then try again.",
            )
        number = self.log.tally(self.name).attempts + 1
        verdict = self._judge(number)
        tally = self.log.add(self.name, verdict.passed)
        if tally.unsaved:  # the verdict still shows, with the one line saying so
            verdict = dataclasses.replace(verdict, note=tally.unsaved)
        self.attempts.append(verdict)
        passed = self.lesson.state.setdefault("exercises_passed", set())
        if verdict.passed:
            passed.add(self.name)
        from ..progress.client import report_attempt

        report_attempt(self.lesson.number, self.name, number, verdict.passed)
        self._stop_robot()
        self.arm()
        return verdict
