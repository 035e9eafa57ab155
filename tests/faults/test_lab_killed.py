"""A SIGKILLed `make lab` leaves nothing running; the next one says so and carries on.

It also opens with no stale tabs: the workspace a lab (or a test's lab) saved stays its own.
"""

from __future__ import annotations

import os
import shutil
import signal
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

import psutil
import pytest
from jupyter_kernels import describe, wait_gone
from lab_terminal import RestTerminal, lab_daemon, rest
from suite_env import independent_env

from course_lib.core.paths import REPO_ROOT

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "browser"))
from lab_server import LabServer

pytestmark = [pytest.mark.ros, pytest.mark.slow]

FOLDER = REPO_ROOT / "test-artifacts" / "faults" / "lab-killed"
STALE_TAB = "notebook:test-artifacts/browser/lab-x/11_beyond_the_tutorial.ipynb"
WORKSPACE = "/lab/api/workspaces/default"


@pytest.fixture
def private_tmp() -> Iterator[dict[str, str]]:
    """Yield the environment of labs with a runtime folder of their own (their markers)."""
    folder = tempfile.mkdtemp(prefix="lk")
    yield independent_env(TMPDIR=folder)
    shutil.rmtree(folder, ignore_errors=True)


def test_killed_lab_leaves_nothing_and_next_lab_says_so(private_tmp) -> None:
    lab = LabServer([], FOLDER, env=private_tmp)
    try:
        terminal = RestTerminal(lab.base_url, lab.token)
        lab_daemon(lab.process.pid)  # the lab's first terminal starts it
        rest(lab.base_url, lab.token, "POST", "/api/kernels")
        # the page saves its open tabs in the workspace, as the browser tests' pages do
        stale = {"data": {STALE_TAB: {"data": {"path": STALE_TAB[9:], "factory": "Notebook"}}}}
        rest(lab.base_url, lab.token, "PUT", WORKSPACE, {**stale, "metadata": {"id": "default"}})
        assert STALE_TAB in rest(lab.base_url, lab.token, "GET", WORKSPACE)["data"]
        tree = [p.pid for p in psutil.Process(lab.process.pid).children(recursive=True)]
        running = describe(tree)
        for part in ("jupyter-lab", "course_lib.ros2.command.daemon", "kernel_launcher"):
            assert part in running, f"{part} is not running:\n{running}"
        assert terminal.shell_pid in tree
        killed_at = time.monotonic()
        os.kill(lab.process.pid, signal.SIGKILL)
        left = wait_gone(tree, 5.0)
        elapsed = time.monotonic() - killed_at
        assert not left, f"running {elapsed:.1f} s after the lab was killed:\n{describe(left)}"
        terminal.close()
    finally:
        lab.stop()

    again = LabServer([], FOLDER, env=private_tmp)
    try:
        said = again.process.text()
        first = said.splitlines()[0]
        assert first == (
            f"The previous lab (pid {lab.process.pid}) ended without stopping cleanly (killed or "
            "crashed): nothing of it was running any more, and its files are removed."
        ), said[:2000]
        # then, maybe, the shared-memory segments killed processes left (shm_segments.py)
        after = [ln for ln in said.splitlines()[1:] if not ln.startswith("Removed ")]
        assert "ROS 2 course: ROS_DOMAIN_ID=" in after[0], said[:2000]
        assert RestTerminal(again.base_url, again.token).run("echo ok-$((6*7))", "ok-42")
        assert STALE_TAB not in rest(again.base_url, again.token, "GET", WORKSPACE)["data"]
    finally:
        again.stop()
    runtime = Path(private_tmp["TMPDIR"]) / f"ros2-course-{os.getuid()}"
    assert not list(runtime.glob("lab-*")) and not list(runtime.glob("workspaces-*"))
