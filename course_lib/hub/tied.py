"""`python -m course_lib.hub.tied CMD ARGS...`: run CMD so that it stops when its parent dies.

The hub starts its proxy and services as children of its own; were the hub killed, they would
live on without it. Started through this module they get SIGTERM the moment their parent dies.
"""

from __future__ import annotations

import os
import signal
import sys

from ..processes.children import set_parent_death_signal

__all__ = ["tie_to_parent", "tied_command"]


def tie_to_parent(sig: int = signal.SIGTERM) -> None:
    """Ask the kernel to send `sig` to this process when its parent dies."""
    set_parent_death_signal(sig, os.getppid())


def tied_command(*argv: str) -> list[str]:
    """Return the command line that runs `argv` tied to its parent (see this module)."""
    return [sys.executable, "-m", "course_lib.hub.tied", *argv]


def main(argv: list[str]) -> int:
    if not argv:
        print("usage: python -m course_lib.hub.tied CMD [ARGS...]", file=sys.stderr)
        return 2
    tie_to_parent()
    os.execvp(argv[0], argv)
    return 1  # not reached: execvp replaces this process


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
