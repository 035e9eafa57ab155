"""Lesson 7 in a real browser: run all cells, see the robot drive, stop it from a terminal."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from pixels import changed_fraction, is_blank
from terminal import Terminal

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = ["07_move_the_robot.ipynb"]
VIEW = 'iframe[title="3D view of the simulated robot"]'
MOVED = 0.002  # share of the view's pixels that change when the robot drives for a second


def _shot(page, folder: Path, name: str) -> tuple[bytes, Path]:  # type: ignore[no-untyped-def]
    path = folder / f"{name}.png"
    png = page.locator(VIEW).screenshot(path=str(path))
    return png, path


def _change_within(page, folder: Path, first: bytes, *, seconds: int) -> tuple[float, Path]:  # type: ignore[no-untyped-def]
    """Screenshot the view once a second until it differs from `first`; return the change."""
    change, path = 0.0, folder / "view_moving_1.png"
    for _ in range(seconds):
        page.wait_for_timeout(1000)  # screenshots a second apart (what is measured)
        later, path = _shot(page, folder, "view_moving_1")
        change = changed_fraction(first, later)
        if change > MOVED:
            break
    return change, path


def _run_all(page) -> None:  # type: ignore[no-untyped-def]
    page.get_by_role("menuitem", name="Run", exact=True).click()
    page.get_by_role("menuitem", name="Run All Cells", exact=True).click()


def _wait_still(page, folder: Path, timeout: float = 10.0) -> float:  # type: ignore[no-untyped-def]
    """Wait until two views a second apart match; return the last change measured."""
    deadline = time.monotonic() + timeout
    before, _ = _shot(page, folder, "stopping_0")
    change = 1.0
    while change > MOVED / 4 and time.monotonic() < deadline:
        page.wait_for_timeout(1000)  # the interval measured, not a wait for a condition
        after, _ = _shot(page, folder, "stopping_1")
        change, before = changed_fraction(before, after), after
    return change


@pytest.fixture(scope="module")
def page(browser, lab):  # type: ignore[no-untyped-def]
    """One browser tab on the lesson, shared by the tests of this module (they run in order)."""
    tab = browser.new_page(viewport={"width": 1280, "height": 1000})
    tab.goto(lab.lab_url(LESSONS[0]))
    yield tab
    tab.close()


def test_lesson7_drives_the_robot_in_the_3d_view(page, artifacts: Path) -> None:
    try:
        page.get_by_text("Python 3 (ipykernel) | Idle").wait_for(timeout=60_000)
        _run_all(page)
        page.get_by_text("Set parameter successful").first.wait_for(timeout=90_000)
        shot = artifacts / "page_after_set.png"
        page.screenshot(path=str(shot))
        # Run All leaves the last cell in view; an off-screen view may not be repainted.
        page.locator(VIEW).first.scroll_into_view_if_needed()
        moving_0, path_0 = _shot(page, artifacts, "view_moving_0")
        assert not is_blank(moving_0), f"the 3D view is blank: {path_0} (page: {shot})"
        change, path_1 = _change_within(page, artifacts, moving_0, seconds=3)
        assert change > MOVED, f"robot did not move in the view ({change:.4f}): {path_0} {path_1}"

        page.wait_for_function(
            "() => ![...document.querySelectorAll('.jp-InputPrompt')]"
            ".some(p => p.textContent.includes('*'))",
            timeout=90_000,
        )
        page.screenshot(path=str(artifacts / "page_done.png"), full_page=True)
        errors = page.locator('[data-mime-type="application/vnd.jupyter.error"]')
        assert errors.count() == 0, f"a cell failed: {errors.first.inner_text()[:2000]}"
    finally:
        page.screenshot(path=str(artifacts / "page_last.png"))


def test_terminal_param_set_stops_the_robot(page, lab, artifacts: Path) -> None:
    """Runs after the lesson test in this module: its kernel and node are still running."""
    terminal = None
    try:
        page.locator(VIEW).first.wait_for(timeout=60_000)
        terminal = Terminal(page, lab.base_url, lab.token)
        listing = terminal.run("ros2 param list", "  velocity")
        assert "/param_vel_node:" in listing, listing
        # Backwards: the lesson already drove the robot towards the box ahead of it.
        terminal.run("ros2 param set /param_vel_node velocity -0.2", "Set parameter successful")
        moving_0, path_0 = _shot(page, artifacts, "view_moving_0")
        page.wait_for_timeout(1000)  # two screenshots a second apart (what is measured)
        moving_1, path_1 = _shot(page, artifacts, "view_moving_1")
        change = changed_fraction(moving_0, moving_1)
        assert change > MOVED, f"-0.2 set in a terminal did not move it: {path_0} {path_1}"
        terminal.run("ros2 param set /param_vel_node velocity 0.0", "Set parameter successful")
        still = _wait_still(page, artifacts)
        assert still <= MOVED / 4, f"robot still moves after 0.0 ({still:.4f}): {artifacts}"
        got = terminal.run("ros2 param get /param_vel_node velocity", "Double value is:")
        assert "Double value is: 0.0" in got, got
    finally:
        if terminal is not None:
            terminal.close()
        page.screenshot(path=str(artifacts / "page_last.png"))
