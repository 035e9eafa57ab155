"""A seeded random walk through the lessons in one lab, each left running.

`WALK_SEED` and `WALK_STEPS` replay a walk (its seed is printed, and every step); the soak
(`make soak`, `WALK_SOAK=1`) walks at least 100 steps at a person's pace (reading between cells
and steps for seconds to minutes, reading lessons cell by cell, making the catalogue's
mistakes; `WALK_PACE=ci` reads for seconds, `none` walks at machine speed) and prints what it
found.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from lesson_checks import LESSONS  # noqa: F401 (the lab_page fixture copies them)
from pace import PERSON_PACE, pace_from_env
from walk import Walker, walk_settings

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

SHORT_STEPS = 10
SOAK_STEPS = 100
# `make test` walks one seed (open, Run All, restart and re-run across lessons 1, 4, 6, 7, 10
# and 11, with take-overs); random seeds are the soak's, until it finds 0 defects in 100 steps
# (the last soak still met ghosts of nodes a kernel restart killed: see issue 20's note).
SHORT_SEED = 762208


# The suite walks the same steps with a fault between them (test_lab_chaos.py: each fault kind
# once); this walk without faults replays a seed on demand (WALK_SEED, WALK_STEPS).
@pytest.mark.skipif(not os.environ.get("WALK_SEED"), reason="the suite's walk is the fault walk")
@pytest.mark.timeout(1200)  # ten steps, each may restart a kernel
def test_a_short_random_walk(lab_page, artifacts: Path) -> None:
    seed, steps = walk_settings(SHORT_STEPS, SHORT_SEED)
    walker = Walker(lab_page, artifacts)
    walker.random_walk(seed, steps)
    assert not walker.defects, walker.report(seed)


@pytest.mark.skipif(not os.environ.get("WALK_SOAK"), reason="a soak: `make soak` runs it")
@pytest.mark.timeout(0)  # as long as WALK_STEPS takes; run by hand, never in CI
def test_soak_random_walk(lab_page, artifacts: Path) -> None:
    seed, steps = walk_settings(SOAK_STEPS)
    walker = Walker(lab_page, artifacts, pace=pace_from_env(PERSON_PACE))
    try:
        walker.random_walk(seed, steps)
    finally:
        for line in walker.summary(seed):
            walker.log(f"soak: {line}")
    assert not walker.defects, walker.report(seed)
