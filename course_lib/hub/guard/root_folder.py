"""A folder of the hub's account alone (0700), made or checked where the hub keeps what no
other account may open or replace: its locks, its routes to learners' servers."""

from __future__ import annotations

import contextlib
import os
import stat
from pathlib import Path

from ...core.errors import CourseError

__all__ = ["root_only_folder"]


def root_only_folder(folder: Path) -> Path:
    """Return `folder`, made if missing, once it is a directory (not a link) of this account
    closed to every other (its mode set to 0700); else raise CourseError saying what is there."""
    with contextlib.suppress(FileExistsError):
        folder.mkdir(mode=0o700)
    info = folder.lstat()
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.geteuid():
        raise CourseError(
            f"{folder} is not a folder of the hub's account (a link, a file or another "
            "account's folder is there).",
            hint=f"remove it (`rm -r {folder}`), then start the hub again.",
        )
    if stat.S_IMODE(info.st_mode) != 0o700:
        folder.chmod(0o700)
    return folder
