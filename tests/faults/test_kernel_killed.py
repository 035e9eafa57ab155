"""A kernel SIGKILLed mid-lesson leaves no course process, and the next kernel starts cleanly."""

from __future__ import annotations

import os
import signal
import time

import pytest
from jupyter_kernels import describe, process_tree, wait_gone

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

LESSON = """
%load_ext course_lib.notebook.magics
from course_lib.session.session import get_session
from course_lib.notebook import start_world
session = get_session()
node = session.run("parameter_tests", "param_vel")
world = start_world(session, show=True)
print("domain", session.domain_id)
"""


def test_sigkilled_kernel_leaves_nothing_and_next_kernel_starts(start_kernel) -> None:
    kernel = start_kernel()
    kernel.ok(LESSON)
    kernel.ok("%ros2 param set /param_vel_node velocity 0.2")
    tree = process_tree(kernel.pid)
    running = describe(tree)
    for part in ("course_lib.sim --serve-view", "param_vel"):
        assert part in running, f"{part} is not running:\n{running}"
    msg_id = kernel.client.execute("world.wait_sim_time(1e9, timeout=600)")  # a running cell
    assert msg_id
    killed_at = time.monotonic()
    os.kill(kernel.pid, signal.SIGKILL)
    left = wait_gone([kernel.pid, *tree], 2.0)
    elapsed = time.monotonic() - killed_at
    assert not left, f"running {elapsed:.1f} s after the kernel was killed:\n{describe(left)}"

    fresh = start_kernel()
    out = fresh.ok(LESSON + "%ros2 param list /param_vel_node\n", timeout=90)
    assert "  velocity\n" in out.text, out.everything
    assert "Traceback" not in out.everything
