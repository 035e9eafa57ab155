"""`make stop`: stop this user's course processes, and say what stopped."""

from __future__ import annotations

from ..processes.stopping import StopReport, stop_course

__all__ = ["stop_all"]


def stop_all(*, everything: bool = False) -> StopReport:
    """Stop this user's course processes of this clone (of every clone with `everything`):
    SIGINT, SIGTERM, SIGKILL (see processes/stopping.py)."""
    return stop_course(everything=everything)
