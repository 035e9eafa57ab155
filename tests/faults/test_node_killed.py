"""The learner's node is killed: its parameters go with it, and a restart brings them back."""

from __future__ import annotations

import os
import re
import signal
from pathlib import Path

import pytest
from jupyter_kernels import wait_gone

pytestmark = [pytest.mark.ros, pytest.mark.slow]

LISTED = """
import time
from course_lib.notebook.magics import run_line
def listed(present, timeout=10.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if ("/param_vel_node:" in run_line("param list").output.stdout) == present:
            return True
        time.sleep(0.05)
    return False
"""


def test_killed_node_loses_its_parameters_until_restarted(start_kernel, tmp_path: Path) -> None:
    params = tmp_path / "param_vel_node.yaml"
    params.write_text("/param_vel_node:\n  ros__parameters:\n    velocity: 0.3\n")
    kernel = start_kernel()
    kernel.ok(
        "%load_ext course_lib.notebook.magics\n"
        "from course_lib.session.session import get_session\n"
        f"node = get_session().run('parameter_tests', 'param_vel', '--ros-args', "
        f"'--params-file', {str(params)!r})\n"
        "print('pid', node.pid)\n" + LISTED
    )
    kernel.ok("assert listed(True)")
    got = kernel.ok("%ros2 param get /param_vel_node velocity")
    assert "Double value is: 0.3" in got.text, got.everything
    pid = int(re.search(r"pid (\d+)", kernel.ok("print('pid', node.pid)").text)[1])

    os.kill(pid, signal.SIGTERM)  # `kill <pid>` from a terminal
    assert not wait_gone([pid], 5.0)
    kernel.ok("assert listed(False), run_line('param list').output.text")
    missing = kernel.ok("%ros2 param get /param_vel_node velocity")
    assert "Node not found" in missing.text, missing.everything

    kernel.ok("node.restart()\nassert listed(True)")
    back = kernel.ok("%ros2 param get /param_vel_node velocity")
    assert "Double value is: 0.3" in back.text, back.everything
    kernel.ok("assert node in get_session().children")
