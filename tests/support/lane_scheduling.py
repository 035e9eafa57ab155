"""xdist's file-by-file scheduling, with the files that wait dealt as one unit of work (one
worker runs them one after the other, beside the workers that use the cores)."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

import pytest
from file_order import scope_of
from xdist.scheduler import LoadFileScheduling

__all__ = ["WaitingLaneScheduling"]


class WaitingLaneScheduling(LoadFileScheduling):
    """`--dist loadfile`, except that the files in `lane` share one unit of work."""

    def __init__(self, config: pytest.Config, log: Any = None, *, lane: Collection[str]) -> None:
        super().__init__(config, log)
        self.lane = frozenset(lane)

    def _split_scope(self, nodeid: str) -> str:
        # a test's unit of work: what xdist's own loadfile and loadgroup schedulers override
        # (xdist is pinned; tests/unit/repo/test_file_order.py drives this class as xdist does)
        return scope_of(nodeid, self.lane)
