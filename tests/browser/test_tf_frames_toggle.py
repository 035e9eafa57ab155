"""The 3D view's "TF frames" box shows and hides the frames /tf describes (issue 12)."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator
from typing import Any

import mujoco
import pytest
from waits import POLL_MS

from course_lib.sim.view.live import LiveView
from course_lib.sim.world.model import build_model

pytestmark = [
    pytest.mark.browser,
    # meshcat's Visualizer(zmq_url=...) drops a first REQ socket of its own without closing it
    pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning"),
]

TF_ROOT = '["meshcat", "tf"]'
SCAN = '["meshcat", "tf", "odom", "base_footprint", "base_link", "base_scan", "<object>"]'


@pytest.fixture
def view() -> Iterator[str]:
    """A meshcat server (this test's child) drawn by LiveView; yields the page's address."""
    server = subprocess.Popen(
        [sys.executable, "-m", "course_lib.viz.server"],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        lines = {}
        assert server.stdout is not None
        while len(lines) < 2:
            key, _, value = server.stdout.readline().strip().partition("=")
            assert key, "the meshcat server stopped before printing its addresses"
            lines[key] = value
        model = build_model()
        data = mujoco.MjData(model)
        mujoco.mj_forward(model, data)
        live = LiveView(lines["zmq_url"], model, data)
        try:
            yield lines["web_url"]
        finally:
            live.close()
    finally:
        server.terminate()
        server.wait(timeout=10)


def _visible(page: Any) -> bool:
    return bool(page.evaluate(f"viewer.scene_tree.find({TF_ROOT}).object.visible"))


def test_tf_frames_start_hidden_and_the_box_shows_them(browser: Any, view: str) -> None:
    page = browser.new_page()
    try:
        page.goto(view)
        page.wait_for_function(
            f"window.viewer && viewer.scene_tree.find({SCAN}).object.type === 'LineSegments'",
            timeout=20_000,
            polling=POLL_MS,
        )
        box = page.locator("#tf-frames")
        assert page.locator("#tf-toggle").inner_text().strip() == "TF frames"
        assert not box.is_checked() and not _visible(page)
        box.check()
        assert _visible(page)
        box.uncheck()
        assert not _visible(page)
    finally:
        page.close()
