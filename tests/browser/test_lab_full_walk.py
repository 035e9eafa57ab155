"""Lessons 1 to 11 in one lab, each left running, then two restarted: one world, true numbers."""

from __future__ import annotations

from pathlib import Path

import pytest
from lesson_checks import LESSONS
from walk import Step, Walker

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

# The two lessons that drive the robot (their figures must come out the same after a restart).
RESTARTED = ["07_move_the_robot.ipynb", "11_beyond_the_tutorial.ipynb"]


@pytest.mark.timeout(1800)  # every lesson, Run All, two restarts: several minutes
def test_every_lesson_in_order_then_two_restarts(lab_page, artifacts: Path) -> None:
    walker = Walker(lab_page, artifacts)
    for name in LESSONS:
        walker.do(Step("open", name))
    for name in RESTARTED:
        walker.do(Step("restart", name))
    walker.do(Step("check_graph", "the lab"))
    lab_page.screenshot(artifacts / "page_last.png")
    assert not walker.defects, walker.report()
