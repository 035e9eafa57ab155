"""Lesson 11 in a real browser: drag the panel's velocity slider, read it back with `ros2`."""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest
from notebook_ui import run_all_cells, wait_all_ran
from terminal import Terminal
from waits import POLL_MS

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSONS = ["11_beyond_the_tutorial.ipynb"]
NODE = "/descriptor_vel_node"
STEP = 0.01  # the velocity descriptor's step (range 0.0 to 0.26)
TARGET = 0.13  # where the drag aims: the middle of the track, far from any value the lesson leaves
SET_OK = "Set parameter successful"


def _slider(page, name: str):  # type: ignore[no-untyped-def]
    """Return the panel's slider row labelled `name`."""
    label = page.locator(".widget-label", has_text=re.compile(rf"^\s*{name}\s*$"))
    return page.locator(".widget-slider").filter(has=label)


def _readout(slider, timeout: float = 20.0) -> float:  # type: ignore[no-untyped-def]
    """Return the slider's readout, once JupyterLab has rendered it (a cell scrolled into
    view is drawn a moment later: its readout is empty until then)."""
    readout = slider.locator(".widget-readout")
    deadline = time.monotonic() + timeout
    # text_content, not inner_text: a cell JupyterLab has not drawn yet is hidden (its text
    # reads '' to inner_text), though its widget holds the value
    while not (text := (readout.text_content() or "").strip()) and time.monotonic() < deadline:
        time.sleep(0.1)
    return float(text)


def _wait_logged(page, command: str, timeout: float = 20_000) -> None:  # type: ignore[no-untyped-def]
    """Wait until the panel's log shows `command` then its answer; fail with the log."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    panel = page.locator(".widget-vbox", has_text=f"Parameters of {NODE}").last
    log = panel.locator(".widget-output")
    try:
        page.wait_for_function(
            "([el, text]) => el.innerText.includes(text)",
            arg=[log.element_handle(), f"$ {command}\n{SET_OK}"],
            timeout=timeout,
            polling=POLL_MS,
        )
    except PlaywrightTimeout:
        raise AssertionError(
            f"the panel never printed `{command}` then {SET_OK!r}; its log:\n{log.inner_text()}"
        ) from None


def test_lesson11_panel_slider_sets_the_node(page, lab, artifacts: Path) -> None:
    terminal = None
    try:
        run_all_cells(page)
        velocity = _slider(page, "velocity")
        velocity.wait_for(timeout=60_000)
        wait_all_ran(page, artifacts)  # the kernel handles widget messages only when idle

        # Run All ends with the node restarted from the panel's saved file (travel_time 2.0):
        # it runs, once. The learner sets travel_time 0.0 from a terminal (it drives until
        # velocity is 0.0), so no trip ends and resets velocity before `ros2` reads it.
        terminal = Terminal(page, lab.base_url, lab.token)
        listed, _code = terminal.run_to_end("ros2 node list")
        assert [line.strip() for line in listed.splitlines()].count(NODE) == 1, listed
        terminal.run(f"ros2 param set {NODE} travel_time 0.0", SET_OK, timeout=30)

        # JupyterLab lays out a cell scrolled into view a frame or two later (its cells off
        # screen have no layout, so Playwright may take one for shown): scroll it to the
        # middle, then wait until the handle is shown before reading its box
        velocity.evaluate("el => el.scrollIntoView({block: 'center'})")
        page.wait_for_timeout(1000)
        velocity.evaluate("el => el.scrollIntoView({block: 'center'})")
        velocity.locator(".noUi-handle").wait_for(state="visible", timeout=20_000)
        before = _readout(velocity)
        handle = velocity.locator(".noUi-handle").bounding_box()
        track = velocity.locator(".noUi-target").bounding_box()
        assert handle is not None and track is not None, "the velocity slider is not shown"
        x, y = handle["x"] + handle["width"] / 2, handle["y"] + handle["height"] / 2
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(track["x"] + track["width"] * TARGET / 0.26, y, steps=12)
        page.mouse.up()
        page.wait_for_function(
            "([el, before]) => el.innerText.trim() !== before",
            arg=[velocity.locator(".widget-readout").element_handle(), f"{before:.2f}"],
            timeout=10_000,
            polling=POLL_MS,
        )
        shown = _readout(velocity)
        page.screenshot(path=str(artifacts / "slider_dragged.png"))
        assert abs(shown - TARGET) <= 3 * STEP, f"the drag ended at {shown}, aimed at {TARGET}"
        _wait_logged(page, f"ros2 param set {NODE} velocity {shown!r}")

        terminal.run(f"ros2 param get {NODE} velocity", "Double value is:")
        page.wait_for_function(  # the whole line, up to its end
            r"() => /Double value is: \S+\r?\n/.test(window.__term.out)",
            timeout=5_000,
            polling=POLL_MS,
        )
        got = terminal.output
        value = re.search(r"Double value is: (\S+)\r?\n", got)
        assert value is not None, got
        assert abs(float(value[1]) - shown) <= STEP / 2, f"slider shows {shown}; ros2 says {got}"
    finally:
        if terminal is not None:
            terminal.close()
        page.screenshot(path=str(artifacts / "page_last.png"))
