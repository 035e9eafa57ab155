"""Judge a leftover the test made, though other sessions of this user may reap it first.

Every session reaps this user's leftovers as it starts (`reap_orphans`): in a suite run, the
other workers' sessions do too, and one of them can kill the test's leftover (SIGKILL) before
the test judges it. A suite run lost `test_a_dead_owners_process_is_a_leftover` that way: its
leftover died before it printed that it runs. Such a leftover is started again; any other end,
or a verdict on a leftover still running, counts.
"""

from __future__ import annotations

import signal
import subprocess
import sys
from collections.abc import Callable

__all__ = ["dead_pid", "judge_leftover"]

REAPED = -signal.SIGKILL  # how `reap_orphans` ends a leftover


def dead_pid() -> int:
    """Return the pid of a process that has run and ended (an owner that is gone)."""
    ended = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"],
        capture_output=True,
        text=True,
        check=True,
    )
    return int(ended.stdout)


def _reaped(proc: subprocess.Popen[str], within: float) -> bool:
    """Return True if `proc` ends by SIGKILL within `within` s (a kill lands a moment after
    it is sent: a process another session has just reaped can still look alive)."""
    try:
        return proc.wait(timeout=within) == REAPED
    except subprocess.TimeoutExpired:
        return False


def judge_leftover(
    start: Callable[[], subprocess.Popen[str]],
    judge: Callable[[subprocess.Popen[str]], bool],
    attempts: int = 5,
) -> bool:
    """Start a leftover that prints `up` once it runs its code, then return `judge(it)`.

    A leftover reaped by another session before `judge` has a say (killed before `up`, or
    judged False and found killed) is started again, up to `attempts` times in all.
    """
    for _ in range(attempts):
        proc = start()
        assert proc.stdout is not None
        if proc.stdout.readline() != "up\n":
            if _reaped(proc, 2.0):
                continue
            raise AssertionError(f"the leftover ended before it ran (exit {proc.poll()})")
        verdict = judge(proc)
        if verdict or not _reaped(proc, 0.5):
            return verdict
    raise AssertionError(f"other sessions reaped each of {attempts} leftovers before judging")
