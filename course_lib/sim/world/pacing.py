"""Keep simulated time in step with the wall clock, and decide which stream is due (pure)."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

__all__ = ["Cadence", "Pacer", "Schedule"]


class Pacer:
    """Map simulated time to wall time at a real-time factor (0 = as fast as possible)."""

    def __init__(self, real_time_factor: float = 1.0, *, max_lag_s: float = 0.25) -> None:
        self.real_time_factor = real_time_factor
        self.max_lag_s = max_lag_s
        self._anchor: tuple[float, float] | None = None  # (sim time, wall time)

    def set_factor(self, real_time_factor: float) -> None:
        """Change the real-time factor from now on."""
        self.real_time_factor = real_time_factor
        self._anchor = None

    def restart(self) -> None:
        """Forget the anchor (after a pause or a reset): the next call re-anchors."""
        self._anchor = None

    def delay(self, sim_time: float, wall_time: float, *, slack_s: float = 0.0) -> float:
        """Return how long to sleep before simulated `sim_time` is due; 0 if it already is.

        `slack_s`: a lag the caller chose (it slept through points it takes back to back
        now), which does not count as falling behind.
        """
        if self.real_time_factor <= 0:
            return 0.0
        if self._anchor is None:
            self._anchor = (sim_time, wall_time)
            return 0.0
        sim0, wall0 = self._anchor
        due = wall0 + (sim_time - sim0) / self.real_time_factor
        if wall_time - due > self.max_lag_s + slack_s:  # far behind (machine busy): no race
            self._anchor = (sim_time, wall_time)
            return 0.0
        return max(0.0, due - wall_time)


class Schedule:
    """Streams published every `1/rate` seconds of simulated time, on a common step grid."""

    def __init__(self, rates_hz: Mapping[str, float], timestep_s: float, start_s: float = 0.0):
        self.timestep_s = timestep_s
        self.periods = {
            name: max(1, round(1.0 / (rate * timestep_s))) for name, rate in rates_hz.items()
        }
        self._step = round(start_s / timestep_s)
        self._next = dict.fromkeys(self.periods, self._step)

    def steps_to_next(self) -> int:
        """Return how many physics steps to take until the next stream is due (>= 0)."""
        return max(0, min(self._next.values()) - self._step)

    def steps_until(self, names: Iterable[str]) -> int:
        """Return how many physics steps until the first of `names` is next due (>= 0)."""
        return max(0, min(self._next[name] for name in names) - self._step)

    def advance(self, steps: int) -> list[str]:
        """Record `steps` steps taken; return the streams now due, in a stable order."""
        self._step += steps
        due = [name for name, at in self._next.items() if at <= self._step]
        for name in due:
            period = self.periods[name]
            self._next[name] = (self._step // period + 1) * period
        return due

    @property
    def time_s(self) -> float:
        """Return the simulated time the schedule has reached."""
        return self._step * self.timestep_s

    def rate_hz(self, name: str) -> float:
        """Return the actual rate of a stream after rounding to whole steps."""
        return 1.0 / (self.periods[name] * self.timestep_s) if name in self.periods else math.nan


class Cadence:
    """Wall-clock slots every `period_s` for work done at the physics loop's wakes (the view).

    A wake up to `slack_s` before a slot takes it, as the loop's wakes jitter: a period that is
    a whole number of the loop's periods (25 Hz on a 50 Hz loop) then gives evenly spaced
    slots. A wake more than a period late starts the slots again from itself.
    """

    def __init__(self, period_s: float, slack_s: float) -> None:
        self.period_s = period_s
        self.slack_s = slack_s
        self._next: float | None = None

    def due(self, now: float) -> bool:
        """Return True, and take the slot, if one is due at wall time `now`."""
        if self._next is not None and now < self._next - self.slack_s:
            return False
        self._next = (now if self._next is None else self._next) + self.period_s
        if self._next <= now:  # far behind (a busy machine): no burst to catch up
            self._next = now + self.period_s
        return True
