"""A lab terminal as a learner has it: real bash on a pseudo-terminal, with the lab's rc file.

The shell reads course_lib/shell/lab_bashrc.bash (as a lab's terminal does) in the session's
environment, so `ros2`, `colcon`, `rosdep` and `source /opt/ros/jazzy/setup.bash` behave as
they do in a JupyterLab terminal. Readline and echo are off so the output is only the output.
"""

from __future__ import annotations

import os
import pty
import re
import select
import signal
import subprocess
import time
from collections.abc import Mapping
from pathlib import Path

import psutil

from course_lib.lab.jupyterlab import terminal_shell_command

__all__ = ["LearnerShell"]

_DONE = re.compile(r"<<exit (\d+)>>\n")


class LearnerShell:
    """One terminal: type a command and read what it printed, or start a program and wait."""

    def __init__(self, env: Mapping[str, str], cwd: Path) -> None:
        master, slave = pty.openpty()
        argv = terminal_shell_command()
        argv.insert(1, "--noediting")
        self.proc = subprocess.Popen(
            argv, stdin=slave, stdout=slave, stderr=slave, env=dict(env), cwd=cwd,
            start_new_session=True,
        )  # fmt: skip
        os.close(slave)
        self.fd, self.output = master, ""
        self.type("stty -echo; PS1=''; PS2=''; PROMPT_COMMAND=''")

    def _read(self, timeout: float) -> None:
        ready, _, _ = select.select([self.fd], [], [], timeout)
        if ready:
            try:
                chunk = os.read(self.fd, 65536)
            except OSError:  # the shell ended
                chunk = b""
            self.output += chunk.decode(errors="replace").replace("\r\n", "\n")

    def wait_for(self, pattern: str, start: int = 0, timeout: float = 30.0) -> re.Match[str]:
        """Wait until the output after `start` matches regex `pattern`; return the match."""
        deadline = time.monotonic() + timeout
        while True:
            found = re.search(pattern, self.output[start:])
            if found:
                return found
            if time.monotonic() > deadline:
                raise AssertionError(f"never printed /{pattern}/:\n{self.output[start:][-3000:]}")
            self._read(min(0.2, max(deadline - time.monotonic(), 0.01)))

    def send(self, text: str) -> int:
        """Send keys; return where the output after them starts."""
        start = len(self.output)
        os.write(self.fd, text.encode())
        return start

    def type(self, command: str, timeout: float = 60.0) -> tuple[str, int]:
        """Type one command line and wait for it to finish; return (output, exit code)."""
        start = self.send(f"{command}\nprintf '<<exit %s>>\\n' $?\n")
        found = self.wait_for(_DONE.pattern, start, timeout)
        return self.output[start : start + found.start()], int(found[1])

    def start(self, command: str) -> int:
        """Type a command that keeps running (a node); return where its output starts."""
        return self.send(f"{command}\n")

    def interrupt(self, timeout: float = 15.0) -> tuple[str, int]:
        """Press Ctrl-C; wait for the shell to take commands again; return (output, exit)."""
        self.send("\x03")  # the tty flushes what follows Ctrl-C: wait for the program to end
        shell = psutil.Process(self.proc.pid)
        deadline = time.monotonic() + timeout
        while shell.children() and time.monotonic() < deadline:
            self._read(0.05)
        start = self.send("printf '<<exit %s>>\\n' $?\n")
        found = self.wait_for(_DONE.pattern, start, timeout)
        return self.output[start : start + found.start()], int(found[1])

    def close(self) -> None:
        """End the shell and whatever it still runs (the processes of its session)."""
        members = [p for p in psutil.process_iter() if _session_of(p.pid) == self.proc.pid]
        for process in members:
            # an interactive bash ignores SIGINT: it ends on SIGHUP, as when a terminal closes
            hang_up = process.pid == self.proc.pid
            process.send_signal(signal.SIGHUP if hang_up else signal.SIGINT)
        _, alive = psutil.wait_procs(members, timeout=5)
        for process in alive:
            process.kill()
        self.proc.wait(5)
        os.close(self.fd)


def _session_of(pid: int) -> int | None:
    try:
        return os.getsid(pid)
    except OSError:
        return None
