"""`python -m course_lib.hub.guard.tied CMD ARGS...`: run CMD so it stops when its parent dies.

The hub starts its proxy and services as children of its own; were the hub killed, they would
live on without it. Started through this module they get SIGTERM the moment their parent dies.

The parent names itself (`--parent PID`, written by `tied_command` in the parent): a parent
that died before the child asked for the signal would never send it, and the child's
`getppid()` then names whoever adopted it, so only the pid the parent gave can tell.
"""

from __future__ import annotations

import os
import signal
import sys
from collections.abc import Callable

from ...processes.children import set_parent_death_signal

__all__ = ["tie_to_parent", "tied_command", "tied_preexec"]


def tie_to_parent(sig: int = signal.SIGTERM, *, parent: int | None = None) -> None:
    """Ask the kernel to send `sig` to this process when its parent dies; exit at once if the
    parent is gone already. `parent` is the pid the parent had when it started this process
    (take it before the fork: after, a dead parent's orphan sees its adopter as its parent)."""
    set_parent_death_signal(sig, os.getppid() if parent is None else parent)


def tied_preexec(sig: int = signal.SIGTERM) -> Callable[[], None]:
    """Return a preexec_fn that ties the child to this process (the pid is taken now)."""
    parent = os.getpid()
    return lambda: tie_to_parent(sig, parent=parent)


def tied_command(*argv: str) -> list[str]:
    """Return the command line that runs `argv` tied to this process, its parent to be."""
    return [sys.executable, "-m", "course_lib.hub.guard.tied", "--parent", str(os.getpid()), *argv]


def main(argv: list[str]) -> int:
    parent = None
    if argv[:1] == ["--parent"] and len(argv) >= 2 and argv[1].isdigit():
        parent, argv = int(argv[1]), argv[2:]
    if not argv:
        usage = "usage: python -m course_lib.hub.guard.tied [--parent PID] CMD [ARGS...]"
        print(usage, file=sys.stderr)
        return 2
    tie_to_parent(parent=parent)
    os.execvp(argv[0], argv)
    return 1  # not reached: execvp replaces this process


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
