"""Run All after Kernel > Shut Down All Kernels runs every cell, without asking for a kernel."""

from __future__ import annotations

from pathlib import Path

import pytest
from walk import Step, Walker

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = ["01_setup_check.ipynb", "03_the_simulation.ipynb"]


def test_run_all_after_shutting_down_all_kernels_runs_every_cell(
    lab_page, artifacts: Path
) -> None:
    walker = Walker(lab_page, artifacts)
    for name in LESSONS:
        walker.do(Step("open", name))
    assert not walker.defects, walker.report()

    lab_page.shut_down_all_kernels()  # the menu item, confirmed, as a learner does
    lab_page.screenshot(artifacts / "kernels_shut_down.png")
    for name in LESSONS:  # each: its tab, then Run > Run All Cells (a dialog is a failure)
        walker.do(Step("run_all", name))
    lab_page.screenshot(artifacts / "page_last.png")
    assert not walker.defects, walker.report()
