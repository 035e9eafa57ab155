"""The course's turtlesim steps its turtles once per 16 ms, making up what a late timer owes
(rosject/turtlesim/turtlesim_rclpy/kinematics.py: pure, loaded from its file)."""

from __future__ import annotations

import importlib.util

from course_lib.core.paths import REPO_ROOT

_PATH = REPO_ROOT / "rosject/turtlesim/turtlesim_rclpy/kinematics.py"
_SPEC = importlib.util.spec_from_file_location("turtlesim_kinematics", _PATH)
assert _SPEC is not None and _SPEC.loader is not None
kinematics = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(kinematics)
STEP = kinematics.STEP_NS
SECOND = kinematics.MOST_STEPS_OWED * STEP


def test_a_tick_on_time_makes_one_step_and_an_early_one_none() -> None:
    assert kinematics.steps_due(1_000, 1_000) == ([1_000], 1_000 + STEP)
    assert kinematics.steps_due(1_000, 1_000 - STEP // 2) == ([], 1_000)


def test_a_late_tick_makes_up_each_step_it_owes_at_its_own_time() -> None:
    due, following = kinematics.steps_due(0, 30 * STEP + 5)
    assert due == [k * STEP for k in range(31)] and following == 31 * STEP


def test_far_behind_or_a_clock_gone_back_starts_again_from_now() -> None:
    assert kinematics.steps_due(0, SECOND + 7) == ([SECOND + 7], SECOND + 7 + STEP)
    assert kinematics.steps_due(10 * SECOND, 3) == ([3], 3 + STEP)  # /clock restarted
