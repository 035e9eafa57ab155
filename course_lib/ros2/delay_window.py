"""The window of delays `ros2 topic delay` keeps and the lines it prints (pure)."""

from __future__ import annotations

import math

__all__ = ["DelayWindow", "delay_lines"]


class DelayWindow:
    """The delays of the last `size` messages, kept as ros2topic 0.32.2 keeps them.

    The first message only starts the count (its delay is not kept); a clock that went back
    before it starts the count again. Times are nanoseconds.
    """

    def __init__(self, size: int) -> None:
        self.size = size
        self.delays: list[int] = []
        self._start: int | None = None
        self._latest = 0
        self._reported = 0

    def add(self, received_ns: int, stamp_ns: int) -> None:
        """Count one message, received at `received_ns`, stamped `stamp_ns`."""
        if self._start is None or self._start > received_ns:
            self._start, self.delays = received_ns, []
        else:
            self.delays = [*self.delays, received_ns - stamp_ns][-self.size :]
        self._latest = received_ns

    def report(self) -> str | None:
        """Return the lines printed at a tick: None before the first delay, `no new
        messages` when none came since the last report, else the two lines of figures."""
        if not self.delays:
            return None
        if self._latest == self._reported:
            return "no new messages\n"
        self._reported = self._latest
        return delay_lines(self.delays)


def delay_lines(delays_ns: list[int]) -> str:
    """Return ros2topic's two lines for a window of delays in nanoseconds."""
    n = len(delays_ns)
    mean = sum(delays_ns) / n
    std = math.sqrt(sum((x - mean) ** 2 for x in delays_ns) / n)
    return (
        f"average delay: {mean * 1e-9:.3f}\n\tmin: {min(delays_ns) * 1e-9:.3f}s "
        f"max: {max(delays_ns) * 1e-9:.3f}s std dev: {std * 1e-9:.5f}s window: {n}\n"
    )
