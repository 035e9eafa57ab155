"""Run the hub attack tests (test_hub_attacks.py) where their host is a network of their own.

The lease attack binds every domain lease port of its host for as long as a learner signs in;
on the machine's own network that would leave no ROS domain to the tests running beside it.
In a new network namespace (loopback only, its own ports) with its own hub, every attack is
the same, and nothing else on the machine notices.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from class_hub import start_prebuild
from test_hub_attacks import OWN_NETWORK_ENV

from course_lib.core.paths import REPO_ROOT
from course_lib.hub.guard.wall import wall_problem

pytestmark = [pytest.mark.ros, pytest.mark.slow, pytest.mark.learners_env]

ATTACKS = Path(__file__).with_name("test_hub_attacks.py")
_ENTER = (
    "import os, sys\n"
    "from course_lib.hub.guard.wall import enter_own_network\n"
    "enter_own_network()\n"
    "os.execv(sys.executable, [sys.executable, *sys.argv[1:]])\n"
)


@pytest.mark.timeout(2700)
def test_hub_attacks_in_a_network_of_their_own() -> None:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    problem = wall_problem()
    if problem:
        pytest.skip(f"no network namespace here: {problem}")
    # The private network reaches no package index: the learners' environment is built (or
    # found up to date) here first, as every class hub test shares it.
    build = start_prebuild()
    assert build.wait(timeout=1200) == 0, build.text()[-4000:]
    argv = [
        sys.executable, "-c", _ENTER, "-m", "pytest", str(ATTACKS), "-q", "-rA",
        "-p", "no:cacheprovider", "--timeout", "600",
    ]  # fmt: skip
    # a session of its own: none of this run's pytest settings (PYTEST_ADDOPTS="-n 4" gave it
    # four workers, each starting a hub for the same four accounts), and no table of seconds
    # (COURSE_FILE_SECONDS: it wrote a table of its one file over the suite's, mid-run)
    env = {
        k: v
        for k, v in os.environ.items()
        if not k.startswith("PYTEST_") and k != "COURSE_FILE_SECONDS"
    }
    env[OWN_NETWORK_ENV] = "1"
    result = subprocess.run(
        argv, cwd=REPO_ROOT, env=env, capture_output=True, text=True, timeout=1400
    )
    said = result.stdout[-8000:] + result.stderr[-4000:]
    assert result.returncode == 0, said
    assert "skipped" not in result.stdout.splitlines()[-1], said
