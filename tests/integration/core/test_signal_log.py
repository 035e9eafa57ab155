"""COURSE_SIGNAL_LOG=<file>: every signal the course sends is one line of that file."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from course_lib.core.host.signalling import LOG_ENV
from course_lib.processes.children import spawn


def test_stopping_a_child_logs_each_signal_with_sender_target_and_reason(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    log = tmp_path / "signals.log"
    monkeypatch.setenv(LOG_ENV, str(log))
    program = "import time\ntime.sleep(60)"  # a command line of two lines: still one log line
    child = spawn([sys.executable, "-c", program], name="my-node")
    pid = child.pid
    child.stop(timeout=5.0)
    lines = log.read_text().splitlines()
    assert len(lines) == 2, lines  # SIGINT, then SIGKILL for what it left in its group
    sent = re.escape(f"sends SIGINT to group {pid} (")
    command = re.escape("-c import time time.sleep(60)): stopping my-node")
    assert re.search(rf"^\d+\.\d{{3}} pid \d+ \(\S+\) {sent}.*{command}", lines[0])
    assert f"sends SIGKILL to group {pid} (no such process): what my-node left" in lines[1]
    assert "[test tests/integration/core/test_signal_log.py::" in lines[0]
