"""`make stop` ends a lab terminal's shell with a hang-up, so the shell's jobs end with it.

A lab that stops slowly (a busy host) is escalated: every process still running gets SIGTERM,
then SIGKILL. An interactive shell ignores SIGTERM, and a shell killed by SIGKILL leaves its
jobs running: the learner's `sleep 600 &` outlived `make stop` three times of three in a busy
suite. SIGHUP, what a closing terminal sends, makes the shell hang up its jobs first.
"""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import signal
import subprocess
import sys
from collections.abc import Iterator

import pytest

from course_lib.core.waiting import wait_until
from course_lib.processes.ownership import CourseProcess, read_process
from course_lib.processes.stopping import StopReport, stop_processes

# A terminal server that is slow to stop (it ignores SIGINT and SIGTERM, as a busy JupyterLab
# still shutting down would), with an interactive bash on its pty running a job.
TERMINAL = r"""
import os, pty, re, signal
pid, fd = pty.fork()
if pid == 0:
    signal.signal(signal.SIGHUP, signal.SIG_DFL)  # as from a login shell, even under nohup
    os.execvp("bash", ["bash", "--norc", "--noprofile", "-i"])
signal.signal(signal.SIGINT, signal.SIG_IGN)
signal.signal(signal.SIGTERM, signal.SIG_IGN)
os.write(fd, b"sleep 600 & echo job=$!\n")
seen = b""
while not (found := re.search(rb"job=(\d+)\r?\n", seen)):
    seen += os.read(fd, 1024)
print(f"shell={pid} job={int(found[1])}", flush=True)
while True:
    try:
        if not os.read(fd, 1024):
            break
    except OSError:
        break
"""


@pytest.fixture
def terminal() -> Iterator[tuple[int, int, int]]:
    """Yield the pids of a slow terminal server, its shell, and the shell's job."""
    if shutil.which("bash") is None:
        pytest.skip("no bash here")
    server = subprocess.Popen([sys.executable, "-c", TERMINAL], stdout=subprocess.PIPE, text=True)
    try:
        found = re.fullmatch(r"shell=(\d+) job=(\d+)\n", server.stdout.readline())
        assert found, "the terminal did not start its job"
        shell, job = int(found[1]), int(found[2])
        yield server.pid, shell, job
    finally:
        for pid in (job, shell) if found else ():
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        server.kill()
        server.wait(10)
        server.stdout.close()


def test_a_stopped_terminal_shell_hangs_up_its_job(terminal: tuple[int, int, int]) -> None:
    server, shell, job = terminal
    infos = [read_process(server), read_process(shell)]
    assert all(infos) and infos[1].terminal_shell and not infos[0].terminal_shell
    found = [
        CourseProcess(infos[0], "server", "the test's"),
        CourseProcess(infos[1], "shell", "the test's"),
    ]
    report = StopReport()
    stop_processes(found, 0.2, report)  # the server ignores SIGINT and SIGTERM: escalated
    assert wait_until(lambda: read_process(job) is None, 5.0), "the shell's job outlived it"
    assert {s.name: s.signal for s in report.stopped}["shell"] == "SIGHUP"
