"""`python -m course_lib.hub.tied CMD ARGS...`: run CMD so that it stops when its parent dies.

The hub starts its proxy and services as children of its own; were the hub killed, they would
live on without it. Started through this module they get SIGTERM the moment their parent dies.
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys

__all__ = ["tie_to_parent"]

_PR_SET_PDEATHSIG = 1


def tie_to_parent(sig: int = signal.SIGTERM) -> None:
    """Ask the kernel to send `sig` to this process when its parent dies (exit if it already
    has)."""
    parent = os.getppid()
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0)
    if os.getppid() != parent or parent == 1:
        os._exit(1)


def main(argv: list[str]) -> int:
    if not argv:
        print("usage: python -m course_lib.hub.tied CMD [ARGS...]", file=sys.stderr)
        return 2
    tie_to_parent()
    os.execvp(argv[0], argv)
    return 1  # not reached: execvp replaces this process


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
