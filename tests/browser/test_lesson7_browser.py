"""Lesson 7 in a real browser: run all cells, see the robot drive, stop it from a terminal."""

from __future__ import annotations

from pathlib import Path

import pytest
from notebook_ui import run_all_cells, run_cell, wait_all_ran
from pixels import changed_fraction
from terminal import Terminal
from view import MOVED, VIEW, drive_and_watch, frames_asked
from view import shot as _shot
from view import wait_still as _wait_still

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = ["07_move_the_robot.ipynb"]


def test_lesson7_drives_the_robot_in_the_3d_view(page, artifacts: Path) -> None:
    try:
        run_all_cells(page)
        wait_all_ran(page, artifacts)
        assert page.get_by_text("Set parameter successful").count() >= 2  # 0.2, then 0.0
        # The lesson drives for 3 simulated seconds only; like a learner, set 0.2 again in
        # its cell so that the robot drives for as long as the screenshots take.
        drive = lambda: run_cell(page, "param set /param_vel_node velocity 0.2")  # noqa: E731
        change = drive_and_watch(page, artifacts, drive)
        assert change > MOVED, f"robot did not move in the view ({change:.4f}): {artifacts}"
        run_cell(page, "param set /param_vel_node velocity 0.0")
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
        # a still robot's view draws (almost) nothing: meshcat's own loop asked for 60 frames a
        # second, about a tenth of a core in a browser without a GPU; a robot that settles
        # may still send a few poses
        asked = frames_asked(page)
        assert asked < 30, f"a still robot's view asked for {asked} frames in 2 s"
        # a learner turns the camera with the mouse: the view draws each new angle
        turned_0, _ = _shot(page, artifacts, "camera_0")
        box = page.locator(VIEW).first.bounding_box()
        x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(x + 150, y + 40, steps=10)
        page.mouse.up()
        turned_1, path = _shot(page, artifacts, "camera_1")
        assert changed_fraction(turned_0, turned_1) > MOVED, f"the camera did not turn: {path}"
        got = terminal.run("ros2 param get /param_vel_node velocity", "Double value is:")
        assert "Double value is: 0.0" in got, got
    finally:
        if terminal is not None:
            terminal.close()
        page.screenshot(path=str(artifacts / "page_last.png"))
