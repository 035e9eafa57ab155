"""One subscription to the robot's samples per session, shared by the session's readers.

A kernel reads the samples (sim.world.samples) three ways: the world handle, the live speed
plot and the replay log. Three subscriptions on one node made three DDS readers take and
decode every message, and rclpy's executor woke three times for it, rebuilding its wait set
each time: a driving learner's ROS thread woke 30 times a second (0.017 cores). The feed
takes each message once and hands its samples to every listener in turn.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from typing import Any

from ...session.per_session import PerSession
from ..world.samples import SAMPLES_TOPIC, RobotSample, unpack

__all__ = ["SAMPLES_DEPTH", "SamplesFeed", "samples_feed"]

SAMPLES_DEPTH = 20  # 2 s of samples (a message per 0.1 s) wait while the kernel is busy

Listener = Callable[[list[RobotSample]], None]
_log = logging.getLogger(__name__)


class SamplesFeed:
    """The session's one subscription to the samples, made for the first listener and
    dropped after the last."""

    def __init__(self, session: Any) -> None:
        self._session = session
        self._listeners: list[Listener] = []
        self._lock = threading.Lock()
        self._sub: Any = None

    def add(self, listener: Listener) -> None:
        """Call `listener(samples)` with every message's samples from now on."""
        from std_msgs.msg import Float64MultiArray

        from ...session.quiet_events import quiet_subscription

        with self._lock:
            self._listeners.append(listener)
            if self._sub is None:
                self._sub = self._session.node.create_subscription(
                    Float64MultiArray,
                    SAMPLES_TOPIC,
                    self._on_samples,
                    SAMPLES_DEPTH,
                    event_callbacks=quiet_subscription(),
                )

    def remove(self, listener: Listener) -> None:
        """Stop calling `listener`; the last one out ends the subscription. Idempotent."""
        with self._lock:
            self._listeners = [known for known in self._listeners if known != listener]
            sub, self._sub = (self._sub, None) if not self._listeners else (None, self._sub)
        if sub is not None and not self._session.closed:
            self._session.node.destroy_subscription(sub)

    @property
    def listeners(self) -> int:
        """Return how many listeners the feed has."""
        with self._lock:
            return len(self._listeners)

    def _on_samples(self, msg: Any) -> None:
        samples = unpack(msg.data)
        if not samples:
            return
        with self._lock:
            listeners = list(self._listeners)
        for listener in listeners:
            try:
                listener(samples)
            except Exception:  # one reader's error never silences another: logged, not raised
                _log.exception("a reader of the robot's samples failed")


samples_feed = PerSession(SamplesFeed)  # samples_feed(session): the session's one feed
