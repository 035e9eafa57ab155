"""Replays on the ordinary path: two driving lessons in one lab (one world), then a kernel
restart; each run's self-check links its own page, and the link opens it, playing, in a tab."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = ["07_move_the_robot.ipynb", "11_beyond_the_tutorial.ipynb"]
LINK = re.compile(r"my_files/replays/(lesson\d\d-\d{4}-\d\d-\d\d-\d{6}(?:-\d+)?\.html)")


def _linked(lab_page) -> str:  # type: ignore[no-untyped-def]
    """Return the replay file the self-check of the notebook in front links to."""
    text = lab_page.cell_with("lesson.self_check()").text
    found = LINK.search(text)
    assert found, f"the self-check shows no replay link:\n{text}"
    return found[1]


@pytest.mark.timeout(1200)  # two lessons and a restart, Run All each: minutes
def test_each_run_saves_its_replay_and_the_link_opens(lab_page, artifacts: Path) -> None:
    replays = lab_page.lab.folder / "my_files" / "replays"
    try:
        lab_page.open(LESSONS[0])
        lab_page.run_all()
        first = _linked(lab_page)
        assert first.startswith("lesson07-")
        page = (replays / first).read_text(encoding="utf-8")
        assert page.count('class="mark"') == 2 and "velocity := 0.2" in page

        lab_page.open(LESSONS[1])  # the same world, driven by another node
        lab_page.run_all()
        eleven = _linked(lab_page)
        page = (replays / eleven).read_text(encoding="utf-8")
        assert eleven.startswith("lesson11-") and "/descriptor_vel_node" in page
        assert "travel_time := " in page

        lab_page.show(LESSONS[0])
        lab_page.restart_and_run_all()  # a new kernel: a new run, a new file
        second = _linked(lab_page)
        assert second != first and (replays / first).exists() and (replays / second).exists()

        # the link opens the server's raw file in a browser tab of its own, where it plays
        # (JupyterLab's HTML viewer would show it with scripts off: a still 3D view)
        link = lab_page.page.locator(".jp-NotebookPanel:visible a", has_text=second)
        with lab_page.page.context.expect_page(timeout=30_000) as opened:
            link.click()
        replay = opened.value
        try:
            replay.wait_for_load_state()
            assert "/files/" in replay.url and replay.url.endswith(second), replay.url
            replay.wait_for_function("viewer.animator.actions.length > 0", timeout=30_000)
            time_played = "viewer.animator.actions.reduce((m, a) => Math.max(m, a.time), 0)"
            replay.wait_for_function(f"{time_played} > 0.3", timeout=30_000)  # it plays
            assert replay.locator("#needs-scripts").count() == 0
            replay.screenshot(path=str(artifacts / "replay_tab.png"))
        finally:
            replay.close()
    finally:
        lab_page.screenshot(artifacts / "page_last.png")
