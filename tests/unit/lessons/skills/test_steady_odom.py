"""When a drive's measurement starts: once the robot does what its node was told."""

from __future__ import annotations

from course_lib.lessons.skills.measure import steady_odom
from course_lib.notebook.world import OdomReading
from course_lib.sim.world.kinematics import Pose2D


class ScriptedWorld:
    """/odom of a robot that starts at `start_s` of simulated time and accelerates in 0.1 s
    to 0.2 m/s (a world on a clock of its own: pure, no simulation)."""

    def __init__(self, start_s: float) -> None:
        self.start_s, self.now = start_s, 0.0

    def _at(self, t: float) -> OdomReading:
        speed = 0.2 * min(max(t - self.start_s, 0.0) / 0.1, 1.0)
        return OdomReading(t, Pose2D(0.0, 0.0, 0.0), speed, 0.0)

    def odom(self) -> OdomReading:
        return self._at(self.now)

    def wait_sim_time(self, seconds: float) -> OdomReading:
        self.now = max(self.now, round(seconds, 6))
        return self._at(self.now)


def test_a_robot_that_starts_late_is_waited_for_when_asked() -> None:
    late = ScriptedWorld(start_s=1.6)  # its node's publisher was discovered late
    assert steady_odom(late).linear_mps == 0.0  # 1 s for a robot nobody told to move
    late = ScriptedWorld(start_s=1.6)
    reading = steady_odom(late, still_wait_s=5.0)
    assert reading.linear_mps == 0.2 and 1.6 < reading.time_s < 2.2


def test_a_robot_that_never_starts_is_measured_after_the_wait() -> None:
    assert steady_odom(ScriptedWorld(start_s=99.0), still_wait_s=5.0).time_s >= 5.0
