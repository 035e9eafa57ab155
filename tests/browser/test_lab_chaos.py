"""The lessons' random walk in one lab with a fault between steps (issue 62, `make chaos`):
`CHAOS_SEED` and `CHAOS_FAULTS` replay a walk (its seed and every fault are printed)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from chaos import ChaosWalker, chaos_settings
from lesson_checks import LESSONS  # noqa: F401 (the lab_page fixture copies them)

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]


@pytest.mark.skipif(not os.environ.get("CHAOS_FAULTS"), reason="`make chaos` runs it")
@pytest.mark.timeout(0)  # as long as CHAOS_FAULTS takes; run by hand
def test_chaos_walk(lab_page, artifacts: Path) -> None:
    seed, faults = chaos_settings(100)
    walker = ChaosWalker(lab_page, artifacts)
    try:
        walker.chaos_walk(seed, faults)
    finally:
        for line in [*walker.summary(seed), f"faults: {walker.faults}"]:
            walker.log(f"chaos: {line}")
    assert not walker.defects, walker.report(seed)
