"""What the course draws passes axe's WCAG 2.1 A and AA rules (no critical or serious
violation), in a real lab after each lesson's cells ran: the outputs of its cells (panel,
plots, tables, verdicts) and its 3D view. JupyterLab's own violations are listed apart, not
counted (the course does not draw them)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from accessibility import Violation, audit, report
from notebook_ui import run_all_cells, shut_down_kernel_of, wait_all_ran
from view import VIEW

from course_lib.core.paths import NOTEBOOKS_DIR

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = sorted(p.name for p in NOTEBOOKS_DIR.glob("[0-9][0-9]_*.ipynb"))  # one lab, in turn
OUTPUTS = ".jp-OutputArea-output"  # what the course's cells print and show


def _view_frames(page: Any) -> list[Any]:
    frames = []
    for handle in page.locator(VIEW).element_handles():
        frame = handle.content_frame()
        if frame is not None:
            frames.append(frame)
    return frames


def _audit_lesson(page: Any, axe_js: str) -> dict[str, list[Violation]]:
    course = audit(page, axe_js, [OUTPUTS])
    whole = audit(page, axe_js)
    views = [v for frame in _view_frames(page) for v in audit(frame, axe_js)]
    mine = {(v.rule, v.target) for v in course}
    lab = [v for v in whole if (v.rule, v.target) not in mine and "iframe" not in v.target]
    return {"outputs": course, "view": views, "jupyterlab": lab}


@pytest.mark.parametrize("lesson", LESSONS)
def test_what_the_course_draws_passes_axe(
    browser: Any, lab: Any, lesson: str, axe_js: str, artifacts: Path
) -> None:
    tab = browser.new_page(viewport={"width": 1280, "height": 1000})
    try:
        tab.goto(lab.lab_url(lesson))
        run_all_cells(tab)
        wait_all_ran(tab, artifacts)
        found = _audit_lesson(tab, axe_js)
        text = "\n\n".join(f"{part}: {report(vs)}" for part, vs in found.items())
        (artifacts / "axe.txt").write_text(text, encoding="utf-8")
        print(f"\n{lesson}\n{text}")
        assert not found["outputs"] and not found["view"], text
    finally:
        tab.screenshot(path=str(artifacts / "page_last.png"))
        shut_down_kernel_of(tab, lab.base_url, lab.token, lesson)  # the next lesson's alone
        tab.close()
