"""A background process yields the CPU to what a learner waits for.

The simulation works in the background: it needs a few milliseconds of every 20 ms step and
has 20 ms to take them. A learner's command (a `%ros2` magic, a terminal's `ros2`) wakes a
kernel and a node that a running simulation delays if they are scheduled as its equals. On a
host of several labs, a lower priority for the simulation keeps those commands quick and
costs the simulation nothing while the host has cores to spare.

Linux's niceness is per thread and a new thread inherits it, so a process lowers its own
before it starts threads. With autogroups (Linux's default since 2.6.38), every session is
scheduled as one group against the others, and what counts between sessions is the group's
niceness (`/proc/<pid>/autogroup`): a session leader sets it too. A process that is not a
session leader never writes it, which would lower its whole session (its parent's too).
"""

from __future__ import annotations

import os
import random
import threading
import time
from pathlib import Path

__all__ = ["BACKGROUND_NICENESS", "autogroup_niceness", "yield_cpu"]

# 5: a third of the CPU weight of an ordinary process (8 learners on 2 cores: `%ros2 param
# get` p99 15-20 ms instead of 24-39, the simulations still at real time).
BACKGROUND_NICENESS = 5

_AUTOGROUP = Path("/proc/self/autogroup")


def yield_cpu(niceness: int = BACKGROUND_NICENESS) -> None:
    """Lower this process's priority to `niceness` (never raise it), and its session's too
    if it leads one. Call before starting threads: those started later inherit it.

    Linux lets an ordinary account change an autogroup's niceness once per 100 ms on the
    whole host (EAGAIN otherwise): a class whose worlds start together retries in a thread.
    """
    current = os.getpriority(os.PRIO_PROCESS, 0)
    if current < niceness:
        os.setpriority(os.PRIO_PROCESS, 0, niceness)
    if os.getsid(0) != os.getpid():
        return
    if not _lower_autogroup(niceness):
        threading.Thread(
            target=_retry_autogroup, args=(niceness,), name="yield-cpu", daemon=True
        ).start()


def _lower_autogroup(niceness: int) -> bool:
    """Lower this session's autogroup to `niceness`; False if Linux said "not now"."""
    group = autogroup_niceness()
    if group is None or group >= niceness:
        return True
    try:
        _AUTOGROUP.write_text(str(niceness))
    except BlockingIOError:  # EAGAIN: another change on this host within 100 ms
        return False
    except OSError:  # a kernel without autogroups, or a read-only /proc: nothing to lower
        return True
    return True


def _retry_autogroup(niceness: int, attempts: int = 100) -> None:
    for _ in range(attempts):
        time.sleep(random.uniform(0.1, 0.2))  # apart from the others retrying
        if _lower_autogroup(niceness):
            return


def autogroup_niceness(pid: int | str = "self") -> int | None:
    """Return the niceness of `pid`'s autogroup, or None where there are no autogroups."""
    try:
        text = Path(f"/proc/{pid}/autogroup").read_text()
    except OSError:
        return None
    # "/autogroup-123 nice 0"
    words = text.split()
    return int(words[-1]) if len(words) >= 3 and words[-2] == "nice" else None
