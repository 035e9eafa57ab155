"""Lesson 7's plot: the robot's /odom speed over simulated time, each `velocity` change of the
lesson's node marked (another node's changes are not this plot's story).

The picture is the replay's SVG (`viz.speed_svg`): text the browser draws, a few ms to build,
so a live plot costs its kernel no plotting library and little CPU. The live plot redraws at
most once per REFRESH_S; `still()` and `close()` draw what came since the last redraw before
they end it (issue 59: Run All reaches `plot.still()` within a second of the last redraw, and
the live plot froze about 2.5 s into a 3 s drive)."""

from __future__ import annotations

import logging
import threading
from collections import deque
from typing import Any

from ...sim.view.samples_feed import SamplesFeed, samples_feed
from ...sim.world.samples import RobotSample
from ...viz.speed_svg import speed_svg
from .events import changes_of, subscribe_parameter_events
from .speed_summary import speed_summary

__all__ = ["REFRESH_S", "SpeedPlot"]

_log = logging.getLogger(__name__)

REFRESH_S = 1.0  # the live plot redraws at most this often, and only after new samples
_STILL_MPS = 1e-3  # samples of a robot standing still (speed ~0, unchanged) redraw nothing


class SpeedPlot:
    """Record /odom's speed samples and /parameter_events; show them live or as a still
    picture."""

    def __init__(self, session: Any, *, node: str = "/param_vel_node", window: int = 3000) -> None:
        self.session = session
        self.node = node  # only this node's velocity changes are marked
        self.samples: deque[tuple[float, float]] = deque(maxlen=window)
        self.marks: list[tuple[float, str]] = []
        self._unplaced: list[str] = []  # changes heard before any sample: placed at the first
        self.time_jumps = 0  # simulated time going back: the world restarted, or two worlds
        self._lock = threading.Lock()
        self._draw_lock = threading.Lock()  # one drawing at a time: the last one sent wins
        self._stop = threading.Event()
        self._fresh = threading.Event()  # set by new samples or marks: the picture changed
        self.redraws = 0  # live redraws so far
        self._image: Any = None
        self._thread: threading.Thread | None = None
        self._feed: SamplesFeed | None = samples_feed(session)
        self._feed.add(self._on_samples)
        self._stop_events = subscribe_parameter_events(session, self._on_event)

    def _on_samples(self, samples: list[RobotSample]) -> None:
        for sample in samples:
            self._add(sample.time_s, sample.linear_mps)

    def _add(self, stamp: float, speed: float) -> None:
        with self._lock:
            last = self.samples[-1] if self.samples else None
            if last and stamp < last[0]:
                self.time_jumps += 1
                self.marks.append((stamp, "simulated time went back"))
            self.samples.append((stamp, speed))
            self.marks += [(stamp, label) for label in self._unplaced]
            self._unplaced.clear()
        if last is None or stamp < last[0] or max(abs(speed), abs(speed - last[1])) > _STILL_MPS:
            self._fresh.set()  # a still robot's samples alone do not redraw the plot

    def _on_event(self, msg: Any) -> None:
        changed = [
            c
            for c in changes_of(msg)
            if c.kind == "changed" and c.name == "velocity" and c.node == self.node
        ]
        if not changed:
            return
        number = self._history_number(msg)
        labels = [f"{number}velocity := {c.value:g}" for c in changed]
        with self._lock:
            if self.samples:
                self.marks += [(self.samples[-1][0], label) for label in labels]
            else:  # no simulated time known yet (the subscription is still being matched)
                self._unplaced += labels
        self._fresh.set()

    def _history_number(self, msg: Any) -> str:
        """Return `#n ` where n numbers the same change in `lesson.history()` (the feed
        journals each event before any widget hears it), or '' if the history lacks it."""
        from ..history import node_history

        stamp = msg.stamp.sec + msg.stamp.nanosec * 1e-9
        entries = node_history(self.node, self.session.domain_id, live=False).entries
        found = [e.number for e in entries if e.stamp == stamp and e.name == "velocity"]
        return f"#{found[-1]} " if found else ""

    def snapshot(self) -> tuple[list[tuple[float, float]], list[tuple[float, str]]]:
        """Return copies of the samples (sim time s, m/s) and marks (sim time s, label)."""
        with self._lock:
            return list(self.samples), list(self.marks)

    def svg(self) -> str:
        """Return the plot so far as SVG text, what it shows said in its description."""
        samples, marks = self.snapshot()
        return speed_svg(samples, marks, summary=speed_summary(samples, marks))

    def show(self) -> Any:
        """Display the live plot (redrawn when new samples came, at most once per REFRESH_S,
        until `still()`)."""
        import ipywidgets as widgets
        from IPython.display import display

        self._image = widgets.HTML(value=self.svg())
        display(self._image)
        if self._thread is None:
            self._thread = threading.Thread(target=self._refresh, daemon=True, name="speed-plot")
            self._thread.start()
        return None

    def _refresh(self) -> None:
        """Redraw after new samples, at most once per REFRESH_S; asleep while none come."""
        while True:
            self._fresh.wait()
            if self._stop.is_set() or self.session.closed:
                return
            self._fresh.clear()
            try:
                self._draw()
            except Exception:  # a failed drawing never ends the live plot: the next may work
                _log.exception("the live speed plot could not be redrawn")
            self.redraws += 1
            if self._stop.wait(REFRESH_S):
                return

    def _draw(self, *, final: bool = False) -> str:
        """Show the picture so far in the live widget; return its SVG. Once the plot is
        ended only the final drawing is shown (a late one of the refresh thread is not)."""
        with self._draw_lock:
            svg = self.svg()
            if self._image is not None and (final or not self._stop.is_set()):
                self._image.value = svg
            return svg

    def still(self) -> Any:
        """End the live plot on the whole run so far and return that picture, still.

        As HTML holding the SVG (JupyterLab shows an image/svg+xml output as an <img> with no
        text alternative; inline, the SVG's own title and description are read out).
        """
        from IPython.display import HTML

        self.close()
        return HTML(self._draw(final=True))  # the live widget's last picture, too

    def close(self) -> None:
        """Stop refreshing and listening, then show everything heard in the live plot (the
        samples since its last redraw too); idempotent."""
        self._stop.set()
        self._fresh.set()  # wakes the refresh thread, which then ends
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        self._stop_events()
        if self._feed is not None:
            self._feed.remove(self._on_samples)
        self._feed = None
        self._draw(final=True)
