"""A driving lesson's replay: what it records from `start(N)` on, and the page it writes.

The page (`my_files/replays/lessonNN-<when the lesson started>.html`) holds the 3D motion and
the speed plot with the driven node's parameter changes; it plays offline, with no kernel.
One lesson run is one file (each save rewrites it, atomically); a lesson keeps its latest
`KEEP` files. The speed plot is the lesson's own (`lesson.speed_plot()`) when it showed one,
drawn from the same samples and marks; otherwise the run's /odom speeds and every change of
the driven node's parameters.
"""

from __future__ import annotations

import html
import logging
import threading
import time
from functools import lru_cache
from pathlib import Path
from typing import Any

from ...core.paths import learner_notebooks_dir
from ...core.server_urls import served_file_url
from ..catalogue import LESSONS

__all__ = ["DRIVEN_NODES", "KEEP", "LessonRun", "ReplayLink", "replay_dir"]

_log = logging.getLogger(__name__)

# The lessons whose robot drives, and the node that drives it (its changes are marked).
DRIVEN_NODES = {spec.number: spec.driven_node for spec in LESSONS if spec.driven_node}
KEEP = 5  # replays kept per lesson (the oldest go first)
FPS = 25  # every second /odom message at its 50 Hz: even frames, a compact page


def replay_dir(learner_dir: Path) -> Path:
    """Return the folder of the replays in the learner's folder."""
    return learner_dir / "replays"


def _value(value: Any) -> str:
    return f"{value:g}" if isinstance(value, float) else repr(value)


@lru_cache(maxsize=4)
def _model(settings: Any) -> Any:
    from ...sim.world.model import build_model

    return build_model(settings)


def _relative(path: Path) -> str:
    """Return `path` relative to the learner's notebooks (as a link there), else absolute."""
    try:
        return path.resolve().relative_to(learner_notebooks_dir().resolve()).as_posix()
    except ValueError:
        return str(path)


class ReplayLink:
    """The line a lesson shows for its saved replay: a link that opens it in a browser tab."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.href = _relative(path)  # relative to the notebooks: the name the learner reads
        # in a lab, the server's raw file (it plays: its scripts run, sandboxed); elsewhere
        # (nbval, a plain kernel) the relative name, which JupyterLab opens in its viewer
        self.url = served_file_url(path) or self.href

    def __repr__(self) -> str:
        return f"Replay of this run, saved (opens without a kernel): {self.href}"

    def _repr_html_(self) -> str:
        return (
            "<p>Replay of this run, saved (opens without a kernel): "
            f'<a href="{html.escape(self.url)}" target="_blank">'
            f"{html.escape(self.href)}</a></p>"
        )


class LessonRun:
    """Record a lesson's run (poses, speed, its node's parameter changes) for a replay."""

    def __init__(self, lesson: Any) -> None:
        from ...notebook.widgets.events import subscribe_parameter_events
        from ...sim.view.run_log import run_log

        self.number = lesson.number
        self.node = DRIVEN_NODES[lesson.number]
        self.folder = replay_dir(lesson.learner_dir)
        stamp = time.strftime("%Y-%m-%d-%H%M%S", time.localtime(lesson.started_at))
        self.name = f"lesson{lesson.number:02d}-{stamp}"
        self.path: Path | None = None  # chosen at the first save, then kept
        self.log = run_log(lesson.session, fps=FPS)  # the session's: shared, never destroyed
        self.since = self.log.mark()  # this lesson's run starts now
        self.marks: list[tuple[float, str]] = []
        self._lock = threading.Lock()
        self._stop_events = subscribe_parameter_events(lesson.session, self._on_event)

    def _on_event(self, msg: Any) -> None:
        from ...notebook.widgets.events import changes_of

        changed = [c for c in changes_of(msg) if c.kind == "changed" and c.node == self.node]
        now = self.log.latest_time_s
        if now is None or not changed:
            return
        with self._lock:
            self.marks += [(now, f"{c.name} := {_value(c.value)}") for c in changed]

    def restart(self) -> None:
        """Start the run over (the robot was put back at its start pose)."""
        self.since = self.log.mark()
        with self._lock:
            self.marks.clear()

    def _target(self) -> Path:
        if self.path is None:
            path, n = self.folder / f"{self.name}.html", 1
            while path.exists():  # another kernel's run of this lesson, started this second
                n += 1
                path = self.folder / f"{self.name}-{n}.html"
            self.path = path
        return self.path

    def _prune(self) -> None:
        """Keep this lesson's KEEP newest replays (this run's always among them)."""
        others = [p for p in self.folder.glob(f"lesson{self.number:02d}-*.html") if p != self.path]
        others.sort(key=lambda p: (p.stat().st_mtime, p.name), reverse=True)
        for old in others[KEEP - 1 :]:
            old.unlink(missing_ok=True)

    def speed_picture(self, *, plot: Any = None, run: Any = None) -> str:
        """Return the run's speed plot as SVG: the lesson's own plot's samples and marks when
        it showed one, else the run's /odom speeds and the driven node's changes."""
        from ...notebook.widgets.speed_summary import speed_summary
        from ...viz.speed_svg import speed_svg

        if plot is not None:
            samples, marks = plot.snapshot()
        else:
            run = self.log.run(self.since) if run is None else run
            samples = [(s.time_s, s.speed_mps) for s in run]
            with self._lock:
                marks = list(self.marks)
        title = f"Robot speed from /odom · changes of {self.node}"
        return speed_svg(samples, marks, title=title, summary=speed_summary(samples, marks))

    def save(self, *, plot: Any = None, settings: Any = None) -> ReplayLink | None:
        """Write the run's page (None if no pose was recorded); return its link."""
        from ...sim.view.run_log import replay_frames
        from ...viz.replay import write_replay

        run = self.log.run(self.since)
        if not run:
            return None
        svg = self.speed_picture(plot=plot, run=run)
        model = _model(settings)
        path = write_replay(
            self._target(), model, replay_frames(model, run), fps=FPS, plot_svg=svg
        )
        try:
            self._prune()
        except OSError as error:  # a replay that cannot be deleted is no reason to fail
            _log.warning("could not prune old replays: %s", error)
        return ReplayLink(path)

    def close(self) -> None:
        """Stop listening to parameter events; idempotent (the session's run log stays)."""
        self._stop_events()
