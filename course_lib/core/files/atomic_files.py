"""Write a file so that no reader ever sees half of it: a temporary file, then a rename.

A write killed before its rename leaves its temporary file (`.<name>.<random>.atomic-tmp`);
the next write into that folder removes those older than a minute, so none pile up.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
import time
from pathlib import Path

from .save_error import FileSaveError

__all__ = ["STALE_AFTER_S", "TEMP_SUFFIX", "FileSaveError", "atomic_write", "remove_stale_temps"]

TEMP_SUFFIX = ".atomic-tmp"
# A write in progress changed its temporary file less than this ago (made and written at once,
# then synced and renamed): an older one was left by a write that was killed.
STALE_AFTER_S = 60.0


def atomic_write(path: str | os.PathLike[str], text: str) -> Path:
    """Write `text` to `path` through a temporary file and a rename: never a half-written file.

    Raises:
        FileSaveError: the file could not be written (an OSError: the disk is full, the folder
            is read-only, ...); `path` is as it was before, and no temporary file is left.
    """
    target = Path(path)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        remove_stale_temps(target.parent)
        _write_then_rename(target, text)
    except OSError as error:
        raise FileSaveError(target, error) from error
    return target


def _write_then_rename(target: Path, text: str) -> None:
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=TEMP_SUFFIX)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):  # the first error is the one to tell
            Path(tmp).unlink(missing_ok=True)
        raise


def remove_stale_temps(folder: Path, *, older_than_s: float = STALE_AFTER_S) -> list[Path]:
    """Remove the temporary files that killed writes left in `folder`; return them."""
    cutoff = time.time() - older_than_s
    removed = []
    for leftover in folder.glob(f".*{TEMP_SUFFIX}"):
        with contextlib.suppress(OSError):  # gone meanwhile (its write ended), or not ours
            if leftover.stat().st_mtime < cutoff:
                leftover.unlink()
                removed.append(leftover)
    return removed
