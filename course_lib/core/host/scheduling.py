"""Tell Linux which of the course's processes are background work: the world's physics.

A class puts sixteen learners on two cores. A learner's command (`%ros2 param get`) waits
for its kernel and the tutorial's node to get a core, and sixteen simulations, each waking
tens of times a second, were often the tasks in their way. Batch scheduling (SCHED_BATCH)
keeps a process's share of the CPU and its priority (its nice value) as they were; only its
wake-ups never preempt a running task, so the others' do first. The world keeps real time:
its pacer catches up on the few milliseconds a wake-up may wait.
"""

from __future__ import annotations

import contextlib
import os

__all__ = ["as_background_work", "is_background_work"]


def as_background_work() -> bool:
    """Schedule this thread, and every thread and process it starts from now on, as batch
    work; return False where the system has no such policy (not Linux) or refuses it."""
    if not hasattr(os, "SCHED_BATCH"):
        return False
    try:
        os.sched_setscheduler(0, os.SCHED_BATCH, os.sched_param(0))
    except OSError:
        return False
    return True


def is_background_work(tid: int) -> bool:
    """Return True if thread (or process) `tid` is scheduled as batch work."""
    with contextlib.suppress(OSError, AttributeError):
        return os.sched_getscheduler(tid) == os.SCHED_BATCH
    return False
