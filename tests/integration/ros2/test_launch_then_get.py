"""A command typed right after `ros2 launch ... &` finds the launch's node.

A launch that has not started its nodes yet is a node starting: `ros2 param get` waits for
it (bounded), as it waits for any process of the domain starting a node. Before, the launch
process counted as a `ros2` command, which starts none, and the get said "Node not found" in
3 of 6 tries; the get after nothing starting still answers at once.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from course_lib.core.paths import venv_bin_dir
from course_lib.ros2.node.participants import domain_newcomers

pytestmark = [pytest.mark.ros, pytest.mark.slow]

TRIES = 6
_LAUNCH_THEN_GET = """
ros2 launch parameter_tests test_parameters.launch.py > /dev/null 2>&1 &
launched=$!
ros2 param get /param_vel_node velocity
kill -INT $launched
wait $launched
"""


def test_a_get_typed_right_after_a_launch_finds_its_node(leased_env: dict[str, str]) -> None:
    env = {**leased_env, "PATH": f"{venv_bin_dir()}:{leased_env.get('PATH', '')}"}
    warm = subprocess.run(["ros2", "node", "list"], env=env, capture_output=True, timeout=60)
    assert warm.returncode == 0, warm.stderr  # the daemon up: a cold first call hides the race
    answers = []
    for _ in range(TRIES):
        done = subprocess.run(
            ["bash", "-c", _LAUNCH_THEN_GET], env=env, capture_output=True, text=True, timeout=60
        )
        answers.append(done.stdout.strip() or done.stderr.strip())
    assert answers == ["Double value is: 0.2"] * TRIES, answers
    started = time.monotonic()
    missing = subprocess.run(
        ["bash", "-c", "ros2 param get /no_such_node velocity"],
        env=env, capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert missing.stderr.strip() == "Node not found"
    assert time.monotonic() - started < 5.0, "nothing starts: the answer is quick"


def test_a_starter_is_a_newcomer_until_its_first_child(
    leased_env: dict[str, str], tmp_path: Path
) -> None:
    """`ros2 launch` (here a stand-in named ros2) counts until it has started a child."""
    stand_in = tmp_path / "ros2"
    stand_in.write_text(
        "import subprocess, sys, time\n"
        "time.sleep(1.0)\n"
        "child = subprocess.Popen(['sleep', '20'])\n"
        "print('child', child.pid, flush=True)\n"
        "time.sleep(20)\n"
    )
    domain = int(leased_env["ROS_DOMAIN_ID"])
    starter = subprocess.Popen(
        [sys.executable, str(stand_in), "launch", "parameter_tests", "x.launch.py"],
        env=leased_env, stdout=subprocess.PIPE, text=True,
    )  # fmt: skip
    child = 0
    try:
        time.sleep(0.3)
        assert starter.pid in domain_newcomers(domain)
        assert starter.stdout is not None
        child = int(starter.stdout.readline().split()[1])
        newcomers = domain_newcomers(domain)
        assert starter.pid not in newcomers and child in newcomers, (starter.pid, newcomers)
    finally:
        starter.kill()
        starter.communicate()
        if child:
            os.kill(child, signal.SIGKILL)
