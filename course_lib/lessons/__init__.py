"""The lessons' one set-up line, `lesson = start(N)`, and what the notebooks call after it.

Every notebook's first cell: `from course_lib.lessons import start; lesson = start(7)`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..config.together import load_checked_settings
from .catalogue import TITLES
from .lesson import Lesson
from .report import Check, SelfCheck
from .settings import CourseSettings

__all__ = ["TITLES", "Check", "CourseSettings", "Lesson", "SelfCheck", "current", "start"]

_lessons: dict[int, Lesson] = {}


def _prepare_ipython() -> None:
    """Load `%ros2` and show course errors as messages, not tracebacks (no-op outside IPython)."""
    try:
        from IPython import get_ipython
    except ImportError:
        return
    shell = get_ipython()
    if shell is None:
        return
    shell.extension_manager.load_extension("course_lib.notebook.magics")
    from ..notebook.cell_errors import install

    install(shell)  # course errors as their two lines; a restarted kernel's slips as hints


def start(number: int, *, settings_path: str | None = None) -> Lesson:
    """Start (or restart) lesson `number`: session, `%ros2`, settings; safe to run again.

    Re-running stops the nodes the lesson started and puts the robot back at its start pose
    when the world runs, so the lesson starts over from a clean state.
    """
    from ..lab.takeover import set_label
    from ..notebook.widgets.events import parameter_events
    from ..session.session import get_session
    from .replay import start_recording

    if number not in TITLES:
        raise ValueError(f"there are lessons 1 to {max(TITLES)}, not {number}")
    _prepare_ipython()  # first: a broken setting below then shows as the course's two lines
    course_path = Path(settings_path) if settings_path is not None else None
    settings, _world = load_checked_settings(course_path)  # a ConfigError: file, line, key
    from ..notebook.hints import set_enabled

    set_enabled(settings.show_hints)  # `%ros2` mistakes' hints too, not only exercises'
    session = get_session()
    parameter_events(session)  # listening from now on: no later change is missed (events.py)
    set_label(f"lesson {number}")
    previous = _lessons.get(number)
    lesson = Lesson(number, session, settings)
    if previous is not None and previous.replay is not None:
        previous.replay.close()
    if previous is not None and previous.session is session:
        previous.stop_nodes()
        lesson._world = previous.attached_world  # the same world, kept running
        if lesson._world is not None and lesson._world.alive:
            lesson._world.reset()
    start_recording(lesson)  # a driving lesson records its run for its replay (replay/)
    _lessons[number] = lesson
    print(f"Lesson {number} · {lesson.title}")
    print("Ready: your own ROS 2 session is running and `%ros2` works in this notebook.")
    return lesson


def current(number: int) -> Any:
    """Return lesson `number` if it was started in this kernel, else None."""
    return _lessons.get(number)
