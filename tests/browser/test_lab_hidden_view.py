"""A 3D view whose notebook's tab is in the background is sent nothing, and catches up at once.

Issue 20: lesson 7's view kept drawing the driving robot while lesson 1 was in front (Chromium
runs animation frames in an iframe under `display: none`); when lesson 7's tab came back the
page froze for 15-22 s (Playwright's click on the tab waited that long; 0.2 s without the
view). The viewer page now tells its server when nobody can see it (its pane's intersection
with the top page's viewport) and gets no poses until it is seen again.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from waits import POLL_MS

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = ["07_move_the_robot.ipynb", "01_setup_check.ipynb"]
SHOWN = "() => shown"  # the viewer page's own state (course_lib/viz/viewer_page.py)


def _viewer(page):  # type: ignore[no-untyped-def]
    frames = [f for f in page.frames if "/static" in f.url]
    assert len(frames) == 1, [f.url for f in page.frames]
    return frames[0]


def test_a_view_in_a_background_tab_is_sent_nothing(lab_page, artifacts: Path) -> None:
    ui = lab_page
    ui.open(LESSONS[0])
    ui.run_all()
    ui.open(LESSONS[1])
    ui.run_all()
    ui.show(LESSONS[0])
    ui.add_cell("%ros2 param set /param_vel_node velocity 0.2")  # the robot drives on
    view = _viewer(ui.page)
    view.locator("#meshcat-pane").scroll_into_view_if_needed()
    view.wait_for_function(SHOWN, timeout=10_000, polling=POLL_MS)

    ui.show(LESSONS[1])  # lesson 7's tab in the background: its view is hidden
    view.wait_for_function("() => !shown", timeout=10_000, polling=POLL_MS)
    ui.page.wait_for_timeout(3000)

    ui.show(LESSONS[0])
    view.wait_for_function(SHOWN, timeout=10_000, polling=POLL_MS)
    ui.add_cell("%ros2 param set /param_vel_node velocity 0.0")
    ui.screenshot(artifacts / "view_back.png")
