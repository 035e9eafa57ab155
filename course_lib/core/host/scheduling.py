"""Tell Linux which of the course's processes are background work: the world's physics.

A class puts sixteen learners on two cores. A learner's command (`%ros2 param get`) waits
for its kernel and the tutorial's node to get a core, and sixteen simulations, each waking
tens of times a second, were the tasks most often in their way. Everywhere, a world that is
up runs as batch work (SCHED_BATCH: its wake-ups never preempt a running task; its share of
the CPU stays what it was). On a class's host (CLASS_HOST_ENV set to 1: the hub sets it for
its learners) it also runs at nice CLASS_NICE, and so does its autogroup (Linux gives each
session one share of the CPU; a world is its own session): while a kernel waited for a core,
worlds ran 40% of the time, and at nice 15 the `param get` p99 at 16 learners fell from
25-57 ms to 12.9. Not on a learner's own computer: there the world yields to nothing but its
own lab, and beside programs that keep every core busy a world at nice 15 can fall behind
real time (a lesson's check that the robot had stopped failed once on a loaded test host).
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

__all__ = [
    "CLASS_HOST_ENV",
    "CLASS_NICE",
    "as_background_work",
    "is_background_work",
]

CLASS_HOST_ENV = "COURSE_CLASS_HOST"
CLASS_NICE = 15
_AUTOGROUP = Path("/proc/self/autogroup")


def _background_nice() -> int:
    """Return the nice of background work here: CLASS_NICE on a class's host, else 0."""
    return CLASS_NICE if os.environ.get(CLASS_HOST_ENV) == "1" else 0


def as_background_work() -> bool:
    """Schedule this process as batch work, at CLASS_NICE on a class's host: every thread it
    has, the threads and processes they start from now on, and its session's autogroup if it
    leads its session. Return False where the system has no such policy (not Linux) or
    refuses it.

    A world calls it once it is up: its start (imports, the model, the nodes: about 2 CPU-s)
    keeps the usual weight, so a lab that starts is not kept waiting for its robot.
    """
    if not hasattr(os, "SCHED_BATCH"):
        return False
    nice = _background_nice()
    try:
        _background(0, nice)
    except OSError:
        return False
    for tid in _threads():
        with contextlib.suppress(OSError):  # a thread that has just ended
            _background(tid, nice)
    if nice and os.getsid(0) == os.getpid():  # its own session: the autogroup is its alone
        with contextlib.suppress(OSError):
            _AUTOGROUP.write_text(str(nice))  # absent without CONFIG_SCHED_AUTOGROUP
    return True


def _background(tid: int, nice: int) -> None:
    os.sched_setscheduler(tid, os.SCHED_BATCH, os.sched_param(0))
    if nice:
        os.setpriority(os.PRIO_PROCESS, tid, nice)


def _threads() -> list[int]:
    """Return the ids of this process's threads (none where /proc cannot say)."""
    with contextlib.suppress(OSError):
        return [int(name) for name in os.listdir("/proc/self/task")]
    return []


def is_background_work(tid: int, nice: int = 0) -> bool:
    """Return True if thread (or process) `tid` is scheduled as batch work at `nice`."""
    with contextlib.suppress(OSError, AttributeError):
        return (
            os.sched_getscheduler(tid) == os.SCHED_BATCH
            and os.getpriority(os.PRIO_PROCESS, tid) == nice
        )
    return False
