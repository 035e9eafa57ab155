"""The course's samples of the robot, gathered into messages (sim.world.samples): BATCH_S of
samples to a message, REST_BATCH_S once the robot has rested REST_S and no reader has asked
for fresh ones lately (a learner reading a lesson leaves the robot still for minutes)."""

from __future__ import annotations

from typing import Any

from std_msgs.msg import Float64MultiArray

from ..world.samples import FIELDS, FRESH_HOLD_S, REST_BATCH_S, REST_S, batch_size

__all__ = ["SampleBatches"]


class SampleBatches:
    """The samples waiting for the next message on `publisher`, and when it goes out."""

    def __init__(self, publisher: Any, odom_hz: float) -> None:
        self._publisher = publisher
        self._rows: list[float] = []
        self._batch = batch_size(odom_hz)
        self._rest_batch = batch_size(odom_hz, REST_BATCH_S)
        self.rest_since: float | None = None  # simulated time the robot came to rest
        self._fresh_until = 0.0  # a reader asked for fresh samples: BATCH_S ones until then

    @property
    def read(self) -> bool:
        """Return True if a reader subscribes to the samples."""
        return self._publisher.get_subscription_count() > 0

    def note(self, still: bool, now: float) -> None:
        """Note whether the robot is still at simulated time `now` (its rest starts then)."""
        if not still:
            self.rest_since = None
        elif self.rest_since is None:
            self.rest_since = now

    def fresh(self, now: float) -> None:
        """A reader asked for fresh samples: send those that wait, then BATCH_S ones."""
        self._fresh_until = now + FRESH_HOLD_S
        self.flush()

    def resting(self, now: float) -> bool:
        """Return True while the robot has rested REST_S and no reader asked for fresh
        samples lately: its samples then go out REST_BATCH_S to a message."""
        since = self.rest_since
        return since is not None and now - since >= REST_S and now >= self._fresh_until

    def rows_left(self, now: float) -> int:
        """Return how many more samples the next message waits for."""
        size = self._rest_batch if self.resting(now) else self._batch
        return size - len(self._rows) // len(FIELDS)

    def add(self, row: list[float], now: float) -> None:
        """Add one sample (a row of FIELDS); send the message once it is full."""
        self._rows += row
        if self.rows_left(now) <= 0:
            self.flush()

    def flush(self) -> None:
        """Publish the samples that wait (the course's readers get them now)."""
        if self._rows:
            self._publisher.publish(Float64MultiArray(data=self._rows))
            self._rows = []
