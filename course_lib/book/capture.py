"""What a lesson's kernel keeps for the book: its replay page and its speed plot picture.

The book's recorder runs this as an extra last cell of a driving lesson (`recording`).
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

from ..core.files.atomic_files import atomic_write
from ..lessons.replay import save_replay, speed_picture

__all__ = ["keep_for_book", "replay_name", "speed_name"]


def replay_name(number: int) -> str:
    """Return the file name of lesson `number`'s replay in the book."""
    return f"lesson{number:02d}.html"


def speed_name(number: int) -> str:
    """Return the file name of lesson `number`'s speed plot picture in the book."""
    return f"lesson{number:02d}-speed.svg"


def keep_for_book(lesson: Any, folder: str) -> None:
    """Save `lesson`'s replay and speed plot into `folder`; raise if nothing was recorded."""
    link = save_replay(lesson)
    svg = speed_picture(lesson)
    if link is None or svg is None:
        raise RuntimeError(f"lesson {lesson.number} recorded no motion of the robot")
    target = Path(folder)
    target.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(link.path, target / replay_name(lesson.number))
    atomic_write(target / speed_name(lesson.number), svg)
