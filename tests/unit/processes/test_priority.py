"""A background process lowers its own priority, and its session's only if it leads one."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from course_lib.core.paths import REPO_ROOT
from course_lib.processes.priority import autogroup_niceness

# A child that yields, then says its threads' niceness and its session's (a thread started
# after yield_cpu inherits it).
_CHILD = """
import json, os, threading, time
from course_lib.processes.priority import autogroup_niceness, yield_cpu
yield_cpu(7)
seen = []
worker = threading.Thread(target=lambda: seen.append(os.getpriority(os.PRIO_PROCESS, 0)))
worker.start(); worker.join()
leader = os.getsid(0) == os.getpid()
deadline = time.monotonic() + 10  # a change Linux refused (EAGAIN) is retried in a thread
while leader and autogroup_niceness() not in (None, 7) and time.monotonic() < deadline:
    time.sleep(0.02)
print(json.dumps({"main": os.getpriority(os.PRIO_PROCESS, 0), "thread": seen[0],
                  "group": autogroup_niceness(), "leader": leader}))
"""


def _child(*, new_session: bool, python: str = sys.executable, **popen: object) -> dict:
    env = {**os.environ, "PYTHONPATH": str(REPO_ROOT)}
    done = subprocess.run(
        [python, "-c", _CHILD],
        env=env,
        cwd=REPO_ROOT,
        capture_output=True,
        text=True,
        timeout=60,
        check=True,
        start_new_session=new_session,
        **popen,  # type: ignore[arg-type]
    )
    return json.loads(done.stdout.splitlines()[-1])


def _expected() -> int:
    """7, or this process's niceness if higher (yield_cpu never raises a priority)."""
    return max(7, os.getpriority(os.PRIO_PROCESS, 0))


def test_a_session_leader_lowers_its_threads_and_its_session() -> None:
    got = _child(new_session=True)
    assert got["leader"]
    assert (got["main"], got["thread"]) == (_expected(), _expected())
    if got["group"] is not None:  # a kernel with autogroups (Linux's default)
        assert got["group"] == 7


def test_a_process_in_its_parents_session_leaves_the_session_alone() -> None:
    """It would lower its parent (here the test itself) with it."""
    before = autogroup_niceness()
    got = _child(new_session=False)
    assert not got["leader"]
    assert (got["main"], got["thread"]) == (_expected(), _expected())
    assert got["group"] == before
    assert autogroup_niceness() == before


def test_an_unprivileged_account_yields_too() -> None:
    """A learner of a class hub is an ordinary account: raising niceness needs no privilege."""
    python = shutil.which("python3.11", path="/usr/bin")
    if os.geteuid() != 0 or python is None:
        pytest.skip("needs root (to become nobody) and Debian's world-executable python3.11")
    if _unreadable_by_others():
        pytest.skip("this clone is not readable by other accounts")
    # an autogroup changed a moment ago (a class's worlds starting together): Linux refuses
    # an ordinary account's change within 100 ms of it (EAGAIN), which yield_cpu retries
    with subprocess.Popen(["sleep", "30"], start_new_session=True) as other:
        try:
            Path(f"/proc/{other.pid}/autogroup").write_text("1")
            got = _child(new_session=True, python=python, user=65534, group=65534, extra_groups=[])
        finally:
            other.kill()
    assert (got["main"], got["thread"]) == (_expected(), _expected())
    if got["group"] is not None:
        assert got["group"] == 7


def _unreadable_by_others() -> bool:
    path = REPO_ROOT / "course_lib" / "processes" / "priority.py"
    while path != path.parent:
        mode = path.stat().st_mode
        if not mode & (0o001 if path.is_dir() else 0o004):
            return True
        path = path.parent
    return False
