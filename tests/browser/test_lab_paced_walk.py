"""A walk at a person's pace: lesson 7 read cell by cell, with the reading times of a learner
(seeded), mistakes from the catalogue between right answers, and lesson 11 taking the robot over
in between. The learner looks at the 3D view for 14 s after setting the velocity, as lesson 7
asks: the robot drives on into the red box meanwhile, and every figure must still be right.

`WALK_PACE=person` reads for up to minutes (as `make soak` does).
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
from pace import CI_PACE, pace_from_env
from walk import Step, Walker

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

SEVEN, ELEVEN = "07_move_the_robot.ipynb", "11_beyond_the_tutorial.ipynb"
LESSONS = [SEVEN, ELEVEN]
SET_VELOCITY = "%ros2 param set /param_vel_node velocity 0.2"
READING_SEED = 590  # the reading times between cells
WALK = [
    Step("read_through", SEVEN),
    Step("mistake", SEVEN, "%ros2 param set /param_vel_node velocity 1"),
    Step("mistake", SEVEN, "%ros2 param set /param_vel_node velocity 0.15 m/s"),
    Step("mistake", SEVEN, "%ros2 param get /param_vel velocity"),
    Step("open", ELEVEN),  # its node takes the robot over: lesson 7's node stops
    Step("rerun_cell", SEVEN, SET_VELOCITY),  # its node is gone: the hint says who stopped it
    Step("read_through", SEVEN),  # its `%ros2 run` cell takes the robot back
    Step("check_graph", "the lab"),
]
STOPPED_BY_ELEVEN = "lesson 11 stopped it when it started /descriptor_vel_node"


@pytest.mark.timeout(900)
def test_a_walk_at_a_persons_pace(lab_page, artifacts: Path) -> None:
    walker = Walker(lab_page, artifacts, pace=pace_from_env(CI_PACE))
    walker.reading = random.Random(READING_SEED)
    for step in WALK:
        walker.do(step)
        if step.detail == SET_VELOCITY:
            said = lab_page.cell_with(SET_VELOCITY).text
            if STOPPED_BY_ELEVEN not in said:
                walker.defects.append(f"lesson 7 after lesson 11 should say why: {said}")
    assert not walker.defects, walker.report()
