"""A second /cmd_vel publisher, started in a lab terminal: lesson 7's self-check names it."""

from __future__ import annotations

from pathlib import Path

import pytest
from lab_graph import wait_publishers
from terminal import Terminal
from walk import Step, Walker

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = ["07_move_the_robot.ipynb"]
PUBLISH = 'ros2 topic pub /cmd_vel geometry_msgs/msg/Twist "{linear: {x: 0.0}}"'
LESSON_NODE = "param_vel_node"


def test_a_terminal_publisher_on_cmd_vel_fails_lesson7_self_check(
    lab_page, artifacts: Path
) -> None:
    walker = Walker(lab_page, artifacts)
    walker.do(Step("open", LESSONS[0]))
    assert not walker.defects, walker.report()
    publisher = Terminal(lab_page.page, lab_page.lab.base_url, lab_page.lab.token)
    info = Terminal(lab_page.page, lab_page.lab.base_url, lab_page.lab.token)
    try:
        lessons_own = wait_publishers(info, "/cmd_vel", lambda names: LESSON_NODE in names)
        start = publisher.send(PUBLISH + "\r")
        publisher.wait_for("publishing #1:", start, after=f"`{PUBLISH}`")
        names = wait_publishers(info, "/cmd_vel", lambda names: set(names) - set(lessons_own))
        extra = sorted(set(names) - set(lessons_own))
        assert len(extra) == 1, f"one new publisher expected besides {lessons_own}: {names}"

        checked = lab_page.run_cell(lab_page.cell_with("lesson.self_check()")).text
        lab_page.screenshot(artifacts / "self_check_with_terminal_publisher.png")
        assert "Everything passed" not in checked, f"passed beside {extra[0]}:\n{checked}"
        assert extra[0] in checked, f"the self-check does not name {extra[0]}:\n{checked}"
        still = publisher.wait_for("publishing #", len(publisher.output), after="the self-check")
        assert "publishing #" in still  # the learner's own publisher was left running

        publisher.send("\x03")  # Ctrl-C
        wait_publishers(info, "/cmd_vel", lambda names: extra[0] not in names)
        checked = lab_page.run_cell(lab_page.cell_with("lesson.self_check()")).text
        assert "Everything passed" in checked, checked
    finally:
        publisher.close()
        info.close()
        lab_page.screenshot(artifacts / "page_last.png")
