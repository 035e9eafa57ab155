"""A lesson's replay page opened offline in Chromium: the robot moves, the speed plot shows its
numbered parameter marks and a playhead that follows the animation, and nothing is fetched."""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Any

import pytest
from pixels import changed_fraction, is_blank

from course_lib.sim.view.recorder import plan_frames
from course_lib.sim.world.physics import Simulation
from course_lib.viz.replay import write_replay
from course_lib.viz.speed_svg import speed_svg

pytestmark = [pytest.mark.browser, pytest.mark.sim]

PLAN = [(0.25, 0.0, 2.0), (0.0, 1.5, 2.0), (0.25, 0.0, 3.0)]  # 7 s: forward, turn, forward


def _replay(folder: Path, plan: list[tuple[float, float, float]] = PLAN) -> Path:
    """A replay of a planned drive (real MuJoCo), its speeds and a mark at each leg's start."""
    sim = Simulation()
    frames = plan_frames(sim, plan)
    samples = [(frames[0].time_s, 0.0)] + [
        (
            b.time_s,
            math.hypot(b.qpos[0] - a.qpos[0], b.qpos[1] - a.qpos[1]) / (b.time_s - a.time_s),
        )
        for a, b in itertools.pairwise(frames)
    ]
    t, marks = frames[0].time_s, []
    for linear, angular, seconds in plan:
        marks.append((t, f"velocity := {linear:g}, turn {angular:g}"))
        t += seconds
    return write_replay(
        folder / "lesson07-run.html", sim.model, frames, plot_svg=speed_svg(samples, marks)
    )


ANIMATION_TIME = "viewer.animator.actions.reduce((m, a) => Math.max(m, a.time), 0)"


def _at(page: Any, seconds: float) -> bytes:
    """Seek the animation to `seconds`, let the playhead follow, and shoot the 3D view."""
    page.evaluate(f"viewer.animator.seek({seconds})")
    page.wait_for_function(f"Math.abs({ANIMATION_TIME} - {seconds}) < 0.01")
    page.wait_for_timeout(300)  # a few animation frames: the view and the playhead redraw
    return page.locator("#meshcat-pane canvas").screenshot()


def test_replay_plays_offline_with_its_speed_plot(
    browser: Any, tmp_path: Path, artifacts: Path
) -> None:
    path = _replay(tmp_path)
    context = browser.new_context(offline=True, viewport={"width": 900, "height": 800})
    requested: list[str] = []

    def only_the_file(route: Any) -> None:
        requested.append(route.request.url)
        if route.request.url == path.as_uri():
            route.continue_()
        else:
            route.abort()

    context.route("**/*", only_the_file)
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    try:
        page.goto(path.as_uri())
        canvas = page.locator("#meshcat-pane canvas")
        canvas.wait_for(timeout=20_000)
        page.wait_for_function("viewer.animator.actions.length > 0", timeout=20_000)
        page.wait_for_function(f"{ANIMATION_TIME} > 0.3", timeout=20_000)  # it plays by itself
        # a screenshot of software WebGL takes seconds here: look at two set times instead
        page.evaluate("viewer.animator.pause()")
        head = page.locator("#playhead")
        first, x1 = _at(page, 0.5), float(head.get_attribute("x1") or 0)
        second, x2 = _at(page, 6.0), float(head.get_attribute("x1") or 0)
        (artifacts / "first.png").write_bytes(first)
        (artifacts / "second.png").write_bytes(second)
        plot = page.locator("#speed-plot")
        (artifacts / "plot.png").write_bytes(plot.screenshot())

        assert not is_blank(first), "the 3D view drew nothing"
        moved = changed_fraction(first, second)
        assert moved > 0.002, f"the robot did not move between two times ({moved:.4f})"
        assert x2 > x1, "the playhead did not follow the animation"
        assert page.locator("#needs-scripts").count() == 0
        assert plot.is_visible() and not is_blank(plot.screenshot())
        marks = page.locator("#speed-plot .mark line")
        assert marks.count() == len(PLAN)
        assert all(marks.nth(i).bounding_box()["height"] > 50 for i in range(len(PLAN)))
        legend = page.locator("#speed-plot .legend").all_text_contents()
        assert legend[0].startswith("1 · 0.0 s · velocity := 0.25")
        assert page.locator("#speed-plot polyline.speed").is_visible()
        assert errors == []
        assert requested == [path.as_uri()], f"the page fetched more than itself: {requested}"
    finally:
        context.close()


# The first frame once the replay is loaded takes 4 s, as drawing the scene for the first time
# (compiling its shaders) did on a busy host: ci57's 7 s replay never showed a time over 0.3 s
# in 20 s, three times in a row.
_SLOW_FIRST_FRAME = """(function () {
  var frame = window.requestAnimationFrame.bind(window), held = false;
  window.requestAnimationFrame = function (callback) {
    return frame(function (now) {
      if (!held && window.viewer && window.viewer.animator.actions.length) {
        held = true;
        var end = Date.now() + 4000;
        while (Date.now() < end) {}
      }
      callback(now);
    });
  };
})();"""


def test_a_replay_plays_from_its_start_after_a_slow_first_frame(
    browser: Any, tmp_path: Path
) -> None:
    path = _replay(tmp_path, [(0.25, 0.0, 3.0)])  # 3 s, shorter than the first frame took
    context = browser.new_context(offline=True, viewport={"width": 600, "height": 500})
    context.add_init_script(_SLOW_FIRST_FRAME)  # runs before the page's own scripts
    page = context.new_page()
    try:
        page.goto(path.as_uri())
        page.wait_for_function(f"{ANIMATION_TIME} > 0.3", timeout=20_000)
        page.wait_for_function(f"{ANIMATION_TIME} == 0", timeout=20_000)  # played through once
    finally:
        context.close()


def test_a_replay_has_play_pause_from_the_start_and_a_time_slider(
    browser: Any, tmp_path: Path
) -> None:
    path = _replay(tmp_path, [(0.25, 0.0, 3.0)])
    context = browser.new_context(offline=True, viewport={"width": 700, "height": 600})
    page = context.new_page()
    try:
        page.goto(path.as_uri())
        page.wait_for_function(f"{ANIMATION_TIME} > 0.3", timeout=20_000)  # plays by itself
        toggle = page.get_by_role("button", name="Pause")
        toggle.click()
        paused = page.evaluate(ANIMATION_TIME)
        page.wait_for_timeout(500)
        assert page.evaluate(ANIMATION_TIME) == paused, "Pause did not stop the replay"
        page.get_by_role("button", name="Play").click()
        page.wait_for_function(f"{ANIMATION_TIME} > {paused} + 0.2", timeout=10_000)
        slider = page.get_by_label("Simulated time")
        slider.fill("2.5")  # a keyboard or a drag: the replay stops there
        page.wait_for_function(f"Math.abs({ANIMATION_TIME} - 2.5) < 0.01", timeout=5_000)
        assert page.get_by_role("button", name="Play").is_visible()
        page.get_by_role("button", name="From the start").click()
        page.wait_for_function(f"{ANIMATION_TIME} < 1.0 && {ANIMATION_TIME} > 0", timeout=5_000)
        page.wait_for_function(f"{ANIMATION_TIME} == 0", timeout=20_000)  # played through
        page.get_by_role("button", name="Play").click()  # an ended replay plays again
        page.wait_for_function(f"{ANIMATION_TIME} > 0.3", timeout=10_000)
    finally:
        context.close()
