"""Lessons 1 to 11 in one lab, each left running, then two restarted: one world, true numbers;
and what each lesson draws passes axe's WCAG 2.1 A and AA rules once it ran (no critical or
serious violation in its cells' outputs or its 3D view; JupyterLab's own listed apart)."""

from __future__ import annotations

from pathlib import Path

import pytest
from accessibility import audit_lesson, report
from lesson_checks import LESSONS
from walk import Step, Walker

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

# The two lessons that drive the robot (their figures must come out the same after a restart).
RESTARTED = ["07_move_the_robot.ipynb", "11_beyond_the_tutorial.ipynb"]


@pytest.mark.timeout(1800)  # every lesson, Run All, two restarts: several minutes
def test_every_lesson_in_order_then_two_restarts(lab_page, artifacts: Path, axe_js: str) -> None:
    walker = Walker(lab_page, artifacts)
    found: list[str] = []
    for name in LESSONS:
        walker.do(Step("open", name))
        audited = audit_lesson(lab_page.page, axe_js, with_jupyterlab=name == LESSONS[-1])
        text = "\n".join(f"  {part}: {report(vs)}" for part, vs in audited.items())
        found.append(f"{name}\n{text}")
        if audited["outputs"] or audited["view"]:
            walker.defects.append(f"{name}: axe finds what the course draws inaccessible:\n{text}")
    (artifacts / "axe.txt").write_text("\n\n".join(found), encoding="utf-8")
    for name in RESTARTED:
        walker.do(Step("restart", name))
    walker.do(Step("check_graph", "the lab"))
    lab_page.screenshot(artifacts / "page_last.png")
    assert not walker.defects, walker.report()
