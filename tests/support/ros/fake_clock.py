"""A scripted clock for waits that take `clock` and `sleep`: sleeping moves it by exactly that
much (real sleeps overshoot on a busy host, and a wait's decision must not depend on that)."""

from __future__ import annotations

__all__ = ["FakeClock"]


class FakeClock:
    """A monotonic clock that only sleeping moves."""

    def __init__(self, now: float = 0.0) -> None:
        self.now = now

    def clock(self) -> float:
        return self.now

    def sleep(self, seconds: float) -> None:
        self.now += seconds
