"""Replays of the lessons that drive the robot: recorded from `start(N)`, saved as one
offline page per lesson run (3D motion and speed plot), linked from the lesson.

`lesson.save_replay()` saves and shows the link; a driving lesson's self-check does it too.
"""

from __future__ import annotations

import logging
from typing import Any

from .run import DRIVEN_NODES, KEEP, LessonRun, ReplayLink, replay_dir

__all__ = [
    "DRIVEN_NODES",
    "KEEP",
    "LessonRun",
    "ReplayLink",
    "replay_dir",
    "save_replay",
    "show_replay",
    "speed_picture",
    "start_recording",
]

_log = logging.getLogger(__name__)


def start_recording(lesson: Any) -> None:
    """Start recording `lesson`'s run if its robot drives (a no-op for the other lessons)."""
    if lesson.number in DRIVEN_NODES and lesson.replay is None:
        lesson.replay = LessonRun(lesson)


def save_replay(lesson: Any) -> ReplayLink | None:
    """Write `lesson`'s replay page; return its link (None: nothing was recorded)."""
    if lesson.replay is None:
        return None
    world = lesson.attached_world
    settings = world.settings if world is not None else None
    plot = lesson.state.get("speed_plot")
    return lesson.replay.save(plot=plot, settings=settings)


def speed_picture(lesson: Any) -> str | None:
    """Return `lesson`'s speed plot as SVG, as its replay draws it (None: nothing recorded)."""
    if lesson.replay is None:
        return None
    return lesson.replay.speed_picture(plot=lesson.state.get("speed_plot"))


def show_replay(lesson: Any) -> None:
    """Save `lesson`'s replay and show its link; a failure is a one-line note, never raised."""
    from IPython.display import display

    from ...core.files.atomic_files import FileSaveError

    try:
        link = save_replay(lesson)
    except FileSaveError as error:  # a full disk: said in one line, the old replays kept
        print(f"The replay of this run was not saved: {error.reason}. Try: {error.hint}")
        return
    except Exception as error:  # the self-check's result matters more than its replay
        _log.exception("saving the replay failed")
        print(f"The replay of this run could not be saved: {error}")
        return
    if link is not None:
        display(link)
