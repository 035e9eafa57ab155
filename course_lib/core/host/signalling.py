"""Send a signal to a process, and say so: ``COURSE_SIGNAL_LOG=<file>`` logs every one.

Every signal the course sends goes through `send`. Each one is logged (at debug level, and as
one line appended to the file ``COURSE_SIGNAL_LOG`` names, when set): who sends it, to which
process or group (with its command line), why, and the test that runs (``PYTEST_CURRENT_TEST``,
inherited by what a test starts). It is the way to find which part of the course stopped a
process, across every process of a test run.
"""

from __future__ import annotations

import contextlib
import logging
import os
import signal
import time

from . import procfs

__all__ = ["LOG_ENV", "send"]

LOG_ENV = "COURSE_SIGNAL_LOG"
_log = logging.getLogger(__name__)


def _command(pid: int) -> str:
    words = " ".join(procfs.cmdline(pid) or ()).split()  # one line, always
    return " ".join(words)[:160] or "no such process"


def _sender() -> str:
    return os.environ.get("COURSE_PROCESS") or _command(os.getpid()).split(" ", 1)[0]


def _record(pid: int, sig: int, group: bool, reason: str) -> None:
    path = os.environ.get(LOG_ENV)
    if not path and not _log.isEnabledFor(logging.DEBUG):
        return
    target = f"group {pid}" if group else f"pid {pid}"
    test = os.environ.get("PYTEST_CURRENT_TEST", "")
    line = (
        f"{time.time():.3f} pid {os.getpid()} ({_sender()}) sends {signal.Signals(sig).name} "
        f"to {target} ({_command(pid)}): {reason}" + (f" [test {test}]" if test else "")
    )
    _log.debug(line)
    if path:
        with contextlib.suppress(OSError):  # a log that cannot be written never stops a signal
            fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o600)
            try:
                os.write(fd, f"{line}\n".encode())  # one write: lines of processes never mix
            finally:
                os.close(fd)


def send(pid: int, sig: int, *, reason: str, group: bool = False) -> None:
    """Send `sig` to process `pid` (to its process group if `group`), as os.kill does.

    Raises ProcessLookupError or PermissionError as os.kill and os.killpg do.
    """
    _record(pid, sig, group, reason)
    if group:
        os.killpg(pid, sig)
    else:
        os.kill(pid, sig)
