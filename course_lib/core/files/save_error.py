"""A file the course could not write, said as the learner reads it: which file, why, what now.

Still an OSError (code that catches OSError keeps working), and a CourseError (a notebook shows
its message, not a traceback).
"""

from __future__ import annotations

import errno
import os
from pathlib import Path

from ..errors import CourseError

__all__ = ["FileSaveError", "shown_path"]

_FULL = {errno.ENOSPC: "the disk is full", errno.EDQUOT: "your disk quota is used up"}
_CLOSED = {
    errno.EROFS: "that folder is read-only",
    errno.EACCES: "that folder cannot be written",
    errno.EPERM: "that folder cannot be written",
}
_FREE_SPACE = (
    "free some space (old replays in my_files/replays/, for example), then run the cell again."
)
_ELSEWHERE = "save it under my_files/ (your own folder) instead."
_AGAIN = "run the cell again; if it says the same, tell your instructor what it says."


def shown_path(path: str | os.PathLike[str]) -> str:
    """Return `path` relative to the current folder when it is under it, else absolute."""
    absolute = Path(path).resolve()
    try:
        return str(absolute.relative_to(Path.cwd().resolve()))
    except (ValueError, OSError):  # elsewhere, or the current folder is gone
        return str(absolute)


def _reason_and_hint(error: OSError) -> tuple[str, str]:
    if error.errno in _FULL:
        return _FULL[error.errno], _FREE_SPACE
    if error.errno in _CLOSED:
        return _CLOSED[error.errno], _ELSEWHERE
    return error.strerror or str(error), _AGAIN


class FileSaveError(CourseError, OSError):
    """A file was not written (the disk is full, the folder is read-only, ...); nothing half."""

    def __init__(self, path: str | os.PathLike[str], error: OSError) -> None:
        self.path = Path(path)
        self.shown = shown_path(path)
        self.reason, hint = _reason_and_hint(error)
        kept = os.path.isfile(self.path)  # never raises: a folder it cannot read says False
        self.kept = "The file as it was before is kept." if kept else "No file was written."
        super().__init__(f"{self.shown} was not saved: {self.reason}. {self.kept}", hint=hint)
        self.errno = error.errno
        self.strerror = error.strerror
        self.filename = str(path)  # the file asked for (the OS may name its temporary file)
