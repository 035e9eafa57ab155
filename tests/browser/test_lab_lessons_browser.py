"""Two lessons open in one lab, as a learner leaves them: one robot, one node, one clock."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from notebook_ui import (
    add_cell,
    open_notebook,
    run_all_cells,
    run_cell,
    shut_down_kernel_of,
    wait_all_ran,
)
from terminal import Terminal
from view import MOVED, VIEW, drive_and_watch

from course_lib.core.paths import REPO_ROOT

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = ["03_the_simulation.ipynb", "07_move_the_robot.ipynb"]
LIVE_VIEW = f".jp-NotebookPanel:visible {VIEW}"


@pytest.fixture
def page(browser, lab):  # type: ignore[no-untyped-def]
    """A fresh tab on lesson 3 for each attempt (a rerun must not inherit the last one's)."""
    tab = browser.new_page(viewport={"width": 1280, "height": 1000})
    tab.goto(lab.lab_url(LESSONS[0]))
    yield tab
    tab.close()


def _view_moves(page, artifacts: Path) -> float:  # type: ignore[no-untyped-def]
    """Drive the still robot at 0.2 m/s; return how much the visible 3D view changed."""
    drive = lambda: run_cell(page, "param set /param_vel_node velocity 0.2")  # noqa: E731
    return drive_and_watch(page, artifacts, drive, view=LIVE_VIEW)


def test_lesson7_opened_beside_lesson3_shares_its_robot(page, lab, artifacts: Path) -> None:
    terminal = None
    try:
        run_all_cells(page)
        wait_all_ran(page, artifacts)
        seven = (lab.folder / LESSONS[1]).relative_to(REPO_ROOT)
        open_notebook(page, lab.base_url, str(seven), lab.token)
        run_all_cells(page)
        wait_all_ran(page, artifacts)

        drove = page.get_by_text(re.compile(r"says \d\.\d\d m/s; the robot drove")).inner_text()
        assert "says 0.20 m/s; the robot drove 0.6 m" in drove, drove
        assert add_cell(page, "print('time jumps:', plot.time_jumps)").strip() == "time jumps: 0"

        terminal = Terminal(page, lab.base_url, lab.token)
        nodes = terminal.run("ros2 node list", "/turtlebot3_laserscan")
        assert nodes.count("/mujoco\r\n") == 1, nodes
        assert nodes.count("/param_vel_node\r\n") == 1, nodes

        assert shut_down_kernel_of(page, lab.base_url, lab.token, LESSONS[0]) == 1
        assert _view_moves(page, artifacts) > MOVED, f"robot did not move: {artifacts}"
        run_cell(page, "param set /param_vel_node velocity 0.0")

        # From the top again: the lesson's node stops, the 3D view keeps working.
        run_cell(page, "lesson = start(7)")
        run_cell(page, "%ros2 run parameter_tests param_vel")
        assert _view_moves(page, artifacts) > MOVED, f"view broken after re-run: {artifacts}"
        run_cell(page, "param set /param_vel_node velocity 0.0")
    finally:
        if terminal is not None:
            terminal.close()
        page.screenshot(path=str(artifacts / "page_last.png"))
