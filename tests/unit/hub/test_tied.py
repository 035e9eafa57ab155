"""`course_lib.hub.guard.tied`: a command tied to a parent that died before the tie never runs."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from course_lib.hub.guard.tied import tied_command

# The parent starts a tied `sleep` and exits at once: the child, still starting Python, ties
# itself to a parent that is gone already.
_PARENT = (
    "import os, subprocess, sys\n"
    "from course_lib.hub.guard.tied import tied_command\n"
    "child = subprocess.Popen(tied_command('sleep', '30'), stdout=subprocess.DEVNULL,\n"
    "                         stderr=subprocess.DEVNULL)\n"
    "print(child.pid, flush=True)\n"
    "os._exit(0)\n"
)


def _running(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state not in ("Z", "X")


def test_a_command_whose_parent_died_before_the_tie_does_not_run() -> None:
    done = subprocess.run(
        [sys.executable, "-c", _PARENT], capture_output=True, text=True, timeout=30, check=True
    )
    child = int(done.stdout)
    try:
        deadline = time.monotonic() + 10.0
        while _running(child) and time.monotonic() < deadline:
            time.sleep(0.05)
        alive = _running(child)
        command = Path(f"/proc/{child}/cmdline").read_bytes() if alive else b""
        assert not alive, f"the orphan runs on without its parent: {command!r}"
    finally:
        with contextlib.suppress(ProcessLookupError):  # the test's own, when the check failed
            if _running(child):
                os.kill(child, signal.SIGKILL)


def test_the_command_names_the_parent_it_is_built_in() -> None:
    argv = tied_command("configurable-http-proxy", "--port", "8000")
    assert argv[1:5] == ["-m", "course_lib.hub.guard.tied", "--parent", str(os.getpid())]
    assert argv[5:] == ["configurable-http-proxy", "--port", "8000"]
