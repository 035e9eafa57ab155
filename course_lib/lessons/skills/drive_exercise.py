"""Lesson 7's skill exercise: set velocity while param_vel_node runs to drive D m in T s."""

from __future__ import annotations

from typing import Any

from . import measure
from .exercise_base import SkillExercise, velocity_of
from .judge import DriveAttempt, Verdict, judge_drive
from .requests import learner_requests
from .room import make_room

__all__ = ["DriveExercise"]


class DriveExercise(SkillExercise):
    """Lesson 7: set velocity while param_vel_node runs, so the robot drives D m in T s."""

    name = "07 drive"

    def __init__(self, lesson: Any) -> None:
        super().__init__(lesson)
        self.settings = lesson.settings.drive_exercise

    def task(self) -> str:
        s = self.settings
        return (
            f"Task: set velocity on {self.node} so that the robot drives {s.distance_m:g} m in "
            f"{s.time_s:g} s (± {s.tolerance_m * 100:g} cm); then run the check: it measures the "
            f"next {s.time_s:g} s of simulated time."
        )

    def _judge(self, number: int) -> Verdict:

        s = self.settings
        world = self.lesson.current_world
        moved_back = make_room(world, velocity_of(self.node), s.time_s)
        if moved_back:
            print(moved_back)
        print(f"Measuring the next {s.time_s:g} s of simulated time on /odom ...", flush=True)
        before = measure.steady_odom(world)
        after = world.wait_sim_time(before.time_s + s.time_s)
        driven = measure.distance_m(before.pose, after.pose)
        value = velocity_of(self.node, None)
        elsewhere, other = "", 0.0
        if abs(driven - s.distance_m) > s.tolerance_m:
            target = s.distance_m / s.time_s
            elsewhere, other = measure.node_holding(target, self.node, s.tolerance_m / s.time_s)
        return judge_drive(
            DriveAttempt(driven, value, elsewhere, other, self._refused_velocity()),
            distance_m=s.distance_m,
            time_s=s.time_s,
            tolerance_m=s.tolerance_m,
            node=self.node,
            number=number,
            show_hints=self.lesson.settings.show_hints,
        )

    def _refused_velocity(self) -> str:
        """Return the learner's latest velocity since arming if the node refused it, as typed."""
        if self.armed_at is None:
            return ""
        sent = learner_requests(self.lesson.session.domain_id, self.armed_at, self.node)
        velocities = [r for r in sent if r.name == "velocity"]
        return velocities[-1].text if velocities and velocities[-1].refused else ""
