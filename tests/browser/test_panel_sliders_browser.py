"""Lesson 11's panel in a real browser: each slider's track gives every step of its range at
least a pixel, within the cell, and its readout shows the value rounded to the step (issue 59:
travel_time's 300 steps had a 94 px track, and its readout said 0.00 for a 0.1 step)."""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest
from notebook_ui import add_cell, run_all_cells, wait_all_ran

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.slow]

LESSONS: list[str] = []  # the lab gets the notebook below, not a lesson
NOTEBOOK = "panel_sliders.ipynb"
CELLS = [  # lesson 11's own calls, without its simulation
    "from course_lib.lessons import start\n\nlesson = start(11)",
    "%ros2 run parameter_descriptors descriptor_vel --ros-args -p use_sim_time:=true",
    'panel = lesson.parameter_panel("/descriptor_vel_node")',
]
SLIDERS = {"travel_time": (300, "0.0"), "velocity": (26, "0.00")}  # steps, readout at 0.0
MAXIMA = {"travel_time": "30", "velocity": "0.26"}  # as the descriptors declare them


def _write_notebook(folder: Path) -> None:
    notebook = nbformat.v4.new_notebook()
    notebook.cells = [nbformat.v4.new_code_cell(source) for source in CELLS]
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3"}
    nbformat.write(notebook, folder / NOTEBOOK)


def _slider(page, name: str):  # type: ignore[no-untyped-def]
    """Return the panel's slider row labelled `name`."""
    label = page.locator(".widget-label", has_text=re.compile(rf"^\s*{name}\s*$"))
    return page.locator(".widget-slider").filter(has=label)


@pytest.fixture(scope="module")
def panel_page(browser, lab, tmp_path_factory):  # type: ignore[no-untyped-def]
    """One tab on the notebook above, all of it run (the panel shown), for the module."""
    _write_notebook(lab.folder)
    page = browser.new_page(viewport={"width": 1280, "height": 1000})
    page.goto(lab.lab_url(NOTEBOOK))
    run_all_cells(page)
    wait_all_ran(page, tmp_path_factory.mktemp("run_all"))
    yield page
    page.close()


def test_panel_sliders_have_a_pixel_per_step_and_round_their_readout(
    panel_page, artifacts: Path
) -> None:
    page = panel_page
    try:
        output = page.locator(".jp-OutputArea-output", has_text="Parameters of").first
        output.scroll_into_view_if_needed()
        area = output.bounding_box()
        assert area is not None, "the panel is not shown"
        for name, (steps, readout) in SLIDERS.items():
            row = _slider(page, name)
            row.locator(".noUi-target").wait_for(state="visible", timeout=20_000)
            track = row.locator(".noUi-target").bounding_box()
            box = row.bounding_box()
            assert track is not None and box is not None
            width = track["width"]
            assert width >= steps, f"{name}: a {width:.0f} px track for {steps} steps"
            assert box["x"] + box["width"] <= area["x"] + area["width"] + 1, f"{name} overflows"
            shown = (row.locator(".widget-readout").text_content() or "").strip()
            assert shown == readout, f"{name} reads out {shown!r}"
            # a screen reader hears the handle by its label, its true range, the readout's value
            handle = page.get_by_role("slider", name=name, exact=True)
            said = {k: handle.get_attribute(f"aria-value{k}") for k in ("max", "min", "text")}
            assert said == {"max": MAXIMA[name], "min": "0", "text": readout}, (name, said)
    finally:
        page.screenshot(path=str(artifacts / "page_last.png"), full_page=True)


def _wait_text(page, text: str) -> None:  # type: ignore[no-untyped-def]
    """Wait until the panel shows `text` (sent by the kernel while no cell runs)."""
    panel = page.locator(".widget-vbox", has_text="Parameters of").last
    panel.get_by_text(text).first.wait_for(timeout=20_000)


def test_the_panel_shows_its_node_gone_and_back(panel_page, artifacts: Path) -> None:
    page = panel_page
    velocity = _slider(page, "velocity").locator(".noUi-target")
    save = page.get_by_role("button", name="Save params file")
    try:
        add_cell(page, 'lesson.stop("descriptor_vel")')
        _wait_text(page, "/descriptor_vel_node is not running (stopped at ")
        assert page.locator("code", has_text=CELLS[1]).count() == 1, "no command to start it"
        assert velocity.get_attribute("disabled") is not None, "a slider of a gone node moves"
        assert save.is_disabled()
        page.screenshot(path=str(artifacts / "node_gone.png"), full_page=True)
        add_cell(page, CELLS[1])
        _wait_text(page, "/descriptor_vel_node is running again")
        assert velocity.get_attribute("disabled") is None
        assert save.is_enabled()
    finally:
        page.screenshot(path=str(artifacts / "page_last.png"), full_page=True)
