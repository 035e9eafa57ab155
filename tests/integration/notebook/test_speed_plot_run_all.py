"""Lesson 7 run as Restart Kernel and Run All runs it: every cell queued at once in a real
kernel. The live plot ends on the whole drive, the same picture as `plot.still()` (issue 59:
it froze about 2.5 s into the drive, as still() came within a second of its last redraw and
ended the live plot without drawing what had come since)."""

from __future__ import annotations

import queue
import re
import time
from xml.dom import minidom

import nbformat
import pytest
from jupyter_kernels import Kernel

from course_lib.core.paths import NOTEBOOKS_DIR

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSON = NOTEBOOKS_DIR / "07_move_the_robot.ipynb"
PLOT_CELL = "plot = lesson.speed_plot()"
STILL_CELL = "plot.still()"
WIDGET = "application/vnd.jupyter.widget-view+json"
STOP_MARK = re.compile(r"velocity := 0(?![.\d])")  # the 0.0 set after the drive


def _cells_up_to_still() -> list[str]:
    """Return lesson 7's code cells, from `start(7)` to `plot.still()`."""
    cells = [c.source for c in nbformat.read(LESSON, as_version=4).cells if c.cell_type == "code"]
    return cells[: cells.index(STILL_CELL) + 1]


def _svg(text: str) -> str:
    """Return the <svg> element of `text` (the live widget's value, or the still's HTML)."""
    return minidom.parseString(text).getElementsByTagName("svg")[0].toxml()


class _Outputs:
    """The iopub messages of queued cells: the plot widget's frames and the still picture."""

    def __init__(self, ids: dict[str, str]) -> None:
        self.ids = ids  # message id -> the cell's source
        self.plot_model = ""
        self.frames: list[str] = []  # the live widget's values, in the order sent
        self.still = ""
        self.errors: list[str] = []

    def take(self, msg: dict) -> None:
        kind, content = msg["msg_type"], msg["content"]
        source = self.ids.get(msg["parent_header"].get("msg_id", ""), "")
        if kind == "display_data" and source == PLOT_CELL and WIDGET in content["data"]:
            self.plot_model = content["data"][WIDGET]["model_id"]
        elif kind == "comm_msg" and content["comm_id"] == self.plot_model:
            value = content["data"].get("state", {}).get("value")
            if isinstance(value, str):
                self.frames.append(value)
        elif kind == "execute_result" and source == STILL_CELL:
            self.still = content["data"].get("text/html", "")  # inline: its title is read out
        elif kind == "error":
            self.errors.append(f"{source}: {content['ename']}: {content['evalue']}")


def _run_all(kernel: Kernel, cells: list[str], timeout: float = 180.0) -> _Outputs:
    """Queue every cell at once (as Run All does); collect outputs until the last is idle."""
    ids = {kernel.submit(source): source for source in cells}
    outputs = _Outputs(ids)
    waiting = set(ids)
    deadline = time.monotonic() + timeout
    while waiting and time.monotonic() < deadline:
        try:
            msg = kernel.client.get_iopub_msg(timeout=1.0)
        except queue.Empty:
            continue
        outputs.take(msg)
        parent = msg["parent_header"].get("msg_id")
        if msg["msg_type"] == "status" and msg["content"]["execution_state"] == "idle":
            waiting.discard(parent)
    assert not waiting, f"{len(waiting)} cells still ran after {timeout:g} s"
    return outputs


def test_the_live_plot_ends_on_the_whole_drive_after_run_all() -> None:
    kernel = Kernel()
    try:
        outputs = _run_all(kernel, _cells_up_to_still())
    finally:
        kernel.shutdown()
    assert not outputs.errors, outputs.errors
    assert outputs.plot_model, "the plot cell showed no widget"
    assert outputs.still, "plot.still() showed no picture"
    assert len(outputs.frames) >= 2, f"the live plot was redrawn {len(outputs.frames)} times"
    assert STOP_MARK.search(outputs.still), "the still picture lacks the stop"
    last = outputs.frames[-1]
    assert STOP_MARK.search(last), "the live plot froze before the stop was set"
    assert _svg(last) == _svg(outputs.still), "the live plot ended on another picture"
