"""Tell Linux which of the course's processes are background work: the world's physics.

A class puts sixteen learners on two cores. A learner's command (`%ros2 param get`) waits
for its kernel and the tutorial's node to get a core, and sixteen simulations, each waking
tens of times a second, were the tasks most often in their way: while a kernel waited for a
core, worlds ran 40% of the time. The world runs as batch work (SCHED_BATCH: its wake-ups
never preempt a running task) at nice BACKGROUND_NICE, and so does its autogroup (Linux
gives each session one share of the CPU; a world is its own session): the learners' kernels
and nodes get a core first. A world needs about 0.05 cores and takes the rest of the CPU
nobody else wants; beside two programs keeping each of two cores busy, it still ran at real
time at nice 15 (0.995; 0.72 at nice 19).
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

__all__ = ["BACKGROUND_NICE", "as_background_work", "is_background_work"]

BACKGROUND_NICE = 15
_AUTOGROUP = Path("/proc/self/autogroup")


def as_background_work() -> bool:
    """Schedule this process as batch work at nice BACKGROUND_NICE: every thread it has, the
    threads and processes they start from now on, and its session's autogroup if it leads
    its session. Return False where the system has no such policy (not Linux) or refuses it.

    A world calls it once it is up: starting (imports, the model, the nodes: about 2 CPU-s)
    at that weight beside a lab that starts too took it minutes on a busy host.
    """
    if not hasattr(os, "SCHED_BATCH"):
        return False
    try:
        _background(0)
    except OSError:
        return False
    for tid in _threads():
        with contextlib.suppress(OSError):  # a thread that has just ended
            _background(tid)
    if os.getsid(0) == os.getpid():  # its own session: the autogroup is the world's alone
        with contextlib.suppress(OSError):
            _AUTOGROUP.write_text(str(BACKGROUND_NICE))  # absent without CONFIG_SCHED_AUTOGROUP
    return True


def _background(tid: int) -> None:
    os.sched_setscheduler(tid, os.SCHED_BATCH, os.sched_param(0))
    os.setpriority(os.PRIO_PROCESS, tid, BACKGROUND_NICE)


def _threads() -> list[int]:
    """Return the ids of this process's threads (none where /proc cannot say)."""
    with contextlib.suppress(OSError):
        return [int(name) for name in os.listdir("/proc/self/task")]
    return []


def is_background_work(tid: int) -> bool:
    """Return True if thread (or process) `tid` is scheduled as batch work at
    BACKGROUND_NICE."""
    with contextlib.suppress(OSError, AttributeError):
        return (
            os.sched_getscheduler(tid) == os.SCHED_BATCH
            and os.getpriority(os.PRIO_PROCESS, tid) == BACKGROUND_NICE
        )
    return False
