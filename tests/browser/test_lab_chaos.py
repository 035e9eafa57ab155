"""The lessons' random walk in one lab with a fault between steps (issue 62).

In every run of the suite: a short walk that brings each kind of fault once (a seed of its
own). `make chaos`: a long one, each fault drawn at random; `CHAOS_SEED` and `CHAOS_FAULTS`
replay a walk (its seed and every fault are printed)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from chaos import FAULTS, ChaosWalker, chaos_settings
from lesson_checks import LESSONS  # noqa: F401 (the lab_page fixture copies them)

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]


# The suite's walk: each fault kind once, in this seed's order, with a step of a lesson after
# each (about 3 minutes on 2 busy cores).
EVERY_KIND_SEED = 4021


@pytest.mark.timeout(1200)
def test_each_fault_kind_once_between_steps(lab_page, artifacts: Path) -> None:
    seed, _ = chaos_settings(len(FAULTS), EVERY_KIND_SEED)
    walker = ChaosWalker(lab_page, artifacts)
    try:
        walker.chaos_walk(seed, len(FAULTS), every_kind=True)
    finally:
        for line in [*walker.summary(seed), f"faults: {walker.faults}"]:
            walker.log(f"chaos: {line}")
    assert walker.faults == len(FAULTS)
    assert not walker.defects, walker.report(seed)


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
