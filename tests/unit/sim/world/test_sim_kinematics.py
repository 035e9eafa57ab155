"""Diff-drive kinematics and pacing: pure, no MuJoCo."""

from __future__ import annotations

import math

import pytest

from course_lib.sim.world.kinematics import DiffDrive, quat_from_yaw, wrap_angle, yaw_from_quat
from course_lib.sim.world.pacing import Pacer, Schedule

TB3 = DiffDrive(0.033, 0.287)


def test_straight_drive_turns_both_wheels_equally() -> None:
    left, right = TB3.wheel_speeds(0.2, 0.0)
    assert left == right == pytest.approx(0.2 / 0.033)


def test_positive_yaw_rate_turns_the_right_wheel_faster() -> None:
    left, right = TB3.wheel_speeds(0.0, 0.5)
    assert right > 0 > left
    assert right == pytest.approx(0.5 * 0.287 / 2 / 0.033)


@pytest.mark.parametrize(("v", "w"), [(0.2, 0.0), (0.0, 1.0), (0.1, -0.4), (-0.26, 1.82)])
def test_body_twist_inverts_wheel_speeds(v: float, w: float) -> None:
    assert TB3.body_twist(*TB3.wheel_speeds(v, w)) == pytest.approx((v, w))


def test_rejects_non_positive_geometry() -> None:
    with pytest.raises(ValueError, match="must be positive"):
        DiffDrive(0.0, 0.287)


@pytest.mark.parametrize("yaw", [0.0, 0.3, -1.2, 3.0, -3.1])
def test_yaw_survives_a_quaternion_round_trip(yaw: float) -> None:
    assert yaw_from_quat(*quat_from_yaw(yaw)) == pytest.approx(yaw)


def test_wrap_angle_stays_in_half_open_range() -> None:
    assert wrap_angle(3 * math.pi) == pytest.approx(-math.pi)
    assert wrap_angle(-0.5) == pytest.approx(-0.5)


def test_pacer_waits_for_simulated_time_at_real_time() -> None:
    pacer = Pacer(1.0)
    assert pacer.delay(0.0, 100.0) == 0.0  # anchors
    assert pacer.delay(0.02, 100.005) == pytest.approx(0.015)
    assert pacer.delay(0.02, 100.03) == 0.0


def test_pacer_scales_with_the_real_time_factor() -> None:
    pacer = Pacer(2.0)
    pacer.delay(0.0, 0.0)
    assert pacer.delay(1.0, 0.0) == pytest.approx(0.5)


def test_pacer_never_waits_when_unlimited() -> None:
    pacer = Pacer(0.0)
    assert pacer.delay(10.0, 0.0) == 0.0


def test_pacer_reanchors_instead_of_racing_after_a_stall() -> None:
    pacer = Pacer(1.0, max_lag_s=0.25)
    pacer.delay(0.0, 0.0)
    assert pacer.delay(0.02, 5.0) == 0.0  # 5 s behind: re-anchor
    assert pacer.delay(0.04, 5.0) == pytest.approx(0.02)


def test_pacer_counts_a_chosen_lag_as_no_stall() -> None:
    """A resting world sleeps through up to a second of points and then takes them back to
    back: that lag is the loop's choice (its slack), and re-anchoring on it would lose the
    simulated time slept through (a resting lab's clock fell a second behind per doze)."""
    pacer = Pacer(1.0, max_lag_s=0.25)
    pacer.delay(0.0, 0.0)
    assert pacer.delay(0.02, 1.0, slack_s=1.0) == 0.0  # 0.98 s behind, within the slack
    assert pacer.delay(1.0, 1.0) == 0.0  # the anchor held: simulated 1.0 s is due at 1.0 s
    assert pacer.delay(1.5, 1.0) == pytest.approx(0.5)
    assert pacer.delay(1.52, 3.0, slack_s=1.0) == 0.0  # beyond lag and slack: re-anchor
    assert pacer.delay(1.54, 3.0) == pytest.approx(0.02)


def test_schedule_steps_to_each_due_stream() -> None:
    schedule = Schedule({"odom": 50.0, "scan": 5.0}, 0.002)
    assert schedule.advance(0) == ["odom", "scan"]
    due = []
    for _ in range(10):
        steps = schedule.steps_to_next()
        assert steps == 10
        due.append(schedule.advance(steps))
    assert due.count(["odom"]) == 9 and due[-1] == ["odom", "scan"]
    assert schedule.time_s == pytest.approx(0.2)
    assert schedule.rate_hz("scan") == pytest.approx(5.0)


def test_schedule_says_how_far_the_next_of_some_streams_is() -> None:
    schedule = Schedule({"odom": 50.0, "scan": 5.0}, 0.002)
    schedule.advance(0)
    assert schedule.steps_until(["scan"]) == 100
    assert schedule.steps_until(["odom", "scan"]) == 10
    schedule.advance(schedule.steps_to_next())
    assert schedule.steps_until(["scan"]) == 90
