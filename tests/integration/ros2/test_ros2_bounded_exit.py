"""A `--no-daemon` command's own node is torn down at exit within a bound: Fast DDS can spin for
ever destroying a participant (a `ros2 topic list -t --no-daemon` of the suite printed its
answer, then hung until the test's 60 s timeout killed it)."""

from __future__ import annotations

import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.processes.domain import lease_domain
from course_lib.ros2.node.direct import CLOSE_LIMIT_S, TEARDOWN_DUMPS_ENV
from course_lib.session.session import session_env

pytestmark = pytest.mark.ros

COMMAND = """
import atexit, sys, time
from course_lib.ros2.node.direct import DirectNode
node = DirectNode(domain_id={domain})
if {hang}:
    node.close = lambda: time.sleep(600)  # a teardown that never ends
atexit.register(node.close_at_exit)  # as the command registers it
print("the answer", flush=True)
sys.exit(0)
"""


@pytest.fixture
def domain() -> Iterator[int]:
    lease = lease_domain({})
    yield lease.domain_id
    lease.release()


@pytest.mark.parametrize("hang", [False, True])
def test_the_command_ends_after_its_answer(domain: int, hang: bool, tmp_path: Path) -> None:
    started = time.monotonic()
    done = subprocess.run(
        [sys.executable, "-c", COMMAND.format(domain=domain, hang=hang)],
        env={**session_env(domain), TEARDOWN_DUMPS_ENV: str(tmp_path)},
        capture_output=True,
        text=True,
        timeout=60,
    )
    took = time.monotonic() - started
    assert done.stdout == "the answer\n"
    assert done.stderr == ""  # the watchdog writes no traceback to the terminal
    (dump,) = tmp_path.glob("teardown-*.txt")  # the suite's: where a teardown stuck
    if hang:  # ended by the watchdog: exit 1, a little after the bound
        assert done.returncode == 1
        assert CLOSE_LIMIT_S <= took < CLOSE_LIMIT_S + 20
        assert "in <lambda>" in dump.read_text(), dump.read_text()  # the stuck call's frame
    else:
        assert done.returncode == 0
        assert dump.read_text() == ""
