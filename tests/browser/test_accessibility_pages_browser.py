"""The pages the course serves pass axe's WCAG 2.1 A and AA rules (no critical or serious
violation) and work from a keyboard (issue 61): the live 3D view (meshcat's page), a replay
page, turtlesim's window and the instructor's progress page. The 3D view is one Tab stop while
its controls are closed, opens them by keyboard, and says the robot's pose and speed in words
in a polite live region."""

from __future__ import annotations

import itertools
import re
import time
from collections.abc import Iterator
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import mujoco
import pytest
from accessibility import audit, report
from waits import POLL_MS

from course_lib.hub.progress.page import render_error, render_page
from course_lib.hub.progress.store import ExerciseStats, LessonState
from course_lib.lessons.catalogue import NUMBERS
from course_lib.sim.view.live import LiveView
from course_lib.sim.view.recorder import plan_frames
from course_lib.sim.world.model import build_model
from course_lib.sim.world.physics import Simulation
from course_lib.turtlesim_view import PenLine, Scene, TurtlePose, WindowServer
from course_lib.viz.replay import write_replay
from course_lib.viz.server import serve_in_thread
from course_lib.viz.speed_svg import speed_svg

pytestmark = [pytest.mark.browser, pytest.mark.sim]

DRAWN = (
    "window.viewer && viewer.scene_tree.children.meshcat"
    " && viewer.scene_tree.children.meshcat.children.mujoco"
)
HOST = """<!DOCTYPE html><html lang="en"><head><title>A lesson</title></head><body>
<button id="before">before</button>
<iframe src="%s" title="3D view of the simulated robot" width="800" height="420"></iframe>
<button id="after">after</button></body></html>"""


def _clean(violations: list[Any]) -> None:
    assert not violations, report(violations)


def _open_every_folder(where: Any) -> None:
    """Open every folder of meshcat's panel (their title buttons), then wait for them."""
    where.evaluate(
        """() => {
          for (let round = 0; round < 20; round++) {  // outer folders first, then theirs
            const shut = [...document.querySelectorAll(".dg ul.closed > li.title > span")];
            if (!shut.length) return;
            shut.forEach((button) => button.click());
          }
        }"""
    )
    where.wait_for_function(
        "() => !document.querySelector('.course-folder[aria-expanded=\"false\"]')",
        polling=POLL_MS,
    )


@dataclass(frozen=True)
class World:
    """A meshcat server of this process drawing a still model: its page, the view, the model."""

    url: str
    view: LiveView
    model: mujoco.MjModel
    data: mujoco.MjData

    def drive(self, page: Any, speed_mps: float, seconds: float) -> None:
        """Move the robot straight on at `speed_mps` (wall time), as the simulation would."""
        start, x0 = time.monotonic(), float(self.data.qpos[0])
        while (elapsed := time.monotonic() - start) < seconds:
            self.data.qpos[0] = x0 + speed_mps * elapsed
            mujoco.mj_kinematics(self.model, self.data)
            self.view.update(self.data)
            page.wait_for_timeout(40)  # 25 frames a second, as the simulation sends them


@pytest.fixture
def world() -> Iterator[World]:
    """A meshcat server in this process, drawn by LiveView."""
    server = serve_in_thread()
    model = build_model()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    view = LiveView(server.zmq_url, model, data, local=server)
    try:
        yield World(server.web_url, view, model, data)
    finally:
        view.close()
        server.stop()


def test_the_3d_view_passes_axe_with_its_controls_closed_and_open(
    browser: Any, world: World, axe_js: str
) -> None:
    page = browser.new_page(viewport={"width": 900, "height": 700})
    try:
        page.goto(world.url)
        page.wait_for_function(DRAWN, timeout=20_000, polling=POLL_MS)
        _clean(audit(page, axe_js))  # before issue 61: 107 critical label, html-has-lang
        page.locator("#view-controls").click()
        _open_every_folder(page)
        assert page.locator(".dg.main input").count() > 50
        _clean(audit(page, axe_js))  # every control of the panel named, AA contrast
    finally:
        page.close()


def test_the_3d_view_is_one_tab_stop_and_opens_its_controls_by_keyboard(
    browser: Any, world: World, artifacts: Path
) -> None:
    page = browser.new_page(viewport={"width": 900, "height": 700})
    try:
        page.set_content(HOST % world.url)
        view = page.frame_locator("iframe")
        frame = page.locator("iframe").element_handle().content_frame()
        frame.wait_for_function(DRAWN, timeout=20_000, polling=POLL_MS)

        def focused() -> str:
            outer = page.evaluate("document.activeElement.id || document.activeElement.tagName")
            if outer != "IFRAME":
                return outer
            return "view:" + frame.evaluate(
                "document.activeElement.id || document.activeElement.className"
            )

        page.locator("#before").focus()
        page.keyboard.press("Tab")
        assert focused() == "view:tf-frames"
        page.keyboard.press("Tab")
        assert focused() == "after", "the view's closed controls took Tab stops"
        page.keyboard.press("Shift+Tab")
        page.keyboard.press("ArrowRight")  # the toolbar's other control
        assert focused() == "view:view-controls"
        controls = view.locator("#view-controls")
        assert controls.get_attribute("aria-expanded") == "false"
        page.keyboard.press("Enter")
        assert controls.get_attribute("aria-expanded") == "true"
        assert frame.evaluate("viewer.gui.closed") is False
        page.keyboard.press("Tab")  # into the panel
        inside = "document.activeElement.closest('.dg.main') !== null"
        assert frame.evaluate(inside), f"Tab did not enter the opened controls: {focused()}"
        folder = view.locator(".course-folder", has_text="Lights")
        assert folder.get_attribute("aria-expanded") == "false"
        folder.focus()
        page.keyboard.press("Enter")  # a folder opens by keyboard too
        assert folder.get_attribute("aria-expanded") == "true"
        page.screenshot(path=str(artifacts / "controls_open.png"))
        page.keyboard.press("Escape")  # leaves the panel, closed, back on its button
        assert frame.evaluate("viewer.gui.closed") is True
        assert focused() == "view:view-controls"
        page.keyboard.press("Tab")
        assert focused() == "after"
    finally:
        page.close()


SPEED = re.compile(r"^Robot at x -?\d+\.\d\d m, y -?\d+\.\d\d m, heading -?\d+°, speed (\S+) m/s$")


def test_the_3d_view_says_the_robots_pose_and_speed_politely(browser: Any, world: World) -> None:
    page = browser.new_page(viewport={"width": 900, "height": 500})
    try:
        page.goto(world.url)
        page.wait_for_function(DRAWN, timeout=20_000, polling=POLL_MS)
        line = page.get_by_role("status")
        assert line.get_attribute("aria-live") == "polite" and line.is_visible()
        page.evaluate(
            """() => {
              window.said = [];
              const line = document.getElementById("robot-state");
              new MutationObserver(() => said.push([performance.now(), line.textContent]))
                .observe(line, {childList: true});
            }"""
        )
        world.drive(page, 0.2, seconds=8.0)
        said = page.evaluate("said")
        texts = [text for _, text in said]
        speeds = [float(SPEED.match(text)[1]) for text in texts if SPEED.match(text)]
        assert len(speeds) == len(texts) >= 2, texts
        assert 0.15 <= speeds[-1] <= 0.25, texts
        gaps = [b - a for (a, _), (b, _) in itertools.pairwise(said)]
        assert min(gaps) >= 2400, f"the line changed faster than a person reads: {gaps}"
    finally:
        page.close()


def test_a_replay_page_passes_axe_and_its_controls_open_by_keyboard(
    browser: Any, tmp_path: Path, axe_js: str
) -> None:
    sim = Simulation()
    frames = plan_frames(sim, [(0.25, 0.0, 2.0)])
    svg = speed_svg([(0.0, 0.0), (1.0, 0.25), (2.0, 0.25)], [(0.0, "velocity := 0.25")])
    path = write_replay(tmp_path / "lesson07-run.html", sim.model, frames, plot_svg=svg)
    page = browser.new_page(viewport={"width": 900, "height": 800})
    try:
        page.goto(path.as_uri())
        page.wait_for_function("viewer.animator.actions.length > 0", timeout=20_000)
        _clean(audit(page, axe_js))  # before: 84 critical label, select-name, html-has-lang
        page.get_by_role("button", name="Open Controls").focus()
        page.keyboard.press("Enter")
        toggle = page.get_by_role("button", name="Close Controls")
        assert toggle.get_attribute("aria-expanded") == "true"
        _open_every_folder(page)
        assert page.get_by_label(re.compile(r"^format \(")).evaluate("e => e.tagName") == "SELECT"
        _clean(audit(page, axe_js))
    finally:
        page.close()


def test_the_turtlesim_window_passes_axe_and_says_where_the_turtles_are(
    browser: Any, axe_js: str
) -> None:
    scene = Scene(
        background=(69, 86, 255),
        lines=(PenLine((179, 184, 255), 3, ((249.5, 249.5), (300.0, 249.5))),),
        turtles=(TurtlePose("turtle1", 249.5, 249.5, 0.0),),
    )
    window = WindowServer()
    window.show(lambda: scene, "/turtlesim")
    page = browser.new_page()
    try:
        page.goto(f"http://127.0.0.1:{window.port}/")
        picture = page.get_by_role("img", name="TurtleSim window")
        described = picture.evaluate(
            "svg => svg.getAttribute('aria-labelledby').split(' ')"
            ".map((id) => document.getElementById(id).textContent).join(': ')"
        )
        assert described == (
            "TurtleSim window: turtle1 at x 5.54, y 5.54, theta 0.00 rad; 1 pen line drawn."
        )
        _clean(audit(page, axe_js))
    finally:
        page.close()
        window.stop()


def test_the_progress_page_passes_axe_and_says_passed_and_failed_in_words(
    browser: Any, axe_js: str
) -> None:
    at = datetime(2026, 11, 23, 19, 5, tzinfo=UTC)
    states = [
        LessonState("alice", 7, True, at, "", None),
        LessonState("bob", 3, False, at, "Speed is 0.2", at),
        LessonState("dave", 2, False, None, "The node runs", at),
    ]
    html = render_page(
        ["carol", "alice"],
        states,
        titles={n: f"Lesson {n}" for n in NUMBERS},
        note="Only learners with records are shown: the hub did not answer.",
        exercises=[ExerciseStats("drive", 7, 3, 2, 2.0)],
    )
    page = browser.new_page()
    try:
        page.set_content(html)
        _clean(audit(page, axe_js))  # before: critical meta-refresh (a reload it cannot stop)
        assert page.locator("td.passed").all_inner_texts()[0].startswith("✓ passed")
        assert all("✗ failed" in t for t in page.locator("td.failed").all_inner_texts())
        refresh = page.get_by_label("Refresh every 30 seconds")
        assert refresh.is_checked()
        refresh.uncheck()  # the instructor stops the reloads (WCAG 2.2.1)
        page.set_content(render_error(403, "you are not an admin of this class"))
        _clean(audit(page, axe_js))  # before: serious html-has-lang
    finally:
        page.close()
