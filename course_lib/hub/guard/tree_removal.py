"""Remove a folder tree of any depth, as root, in a folder another account writes.

`shutil.rmtree` recurses once per level: a learner who nested 1,200 folders in their own
socket folder made it raise RecursionError on Python 3.11, even with `ignore_errors=True`,
and the hub's stop ended in a traceback. This walk keeps a list instead of a call stack, holds
a few open folders whatever the depth (not one a level, which runs out of descriptors), never
follows a link, and climbs back only into the very folder it came from (a level moved
elsewhere meanwhile ends the walk: nothing outside the tree is ever removed).
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

__all__ = ["remove_tree"]

_DIRECTORY = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC


def _open_folder(name: str, parent: int) -> int | None:
    """Return a descriptor of folder `name` in `parent`, or None (gone, a link, a file)."""
    try:
        return os.open(name, _DIRECTORY, dir_fd=parent)
    except OSError:
        return None


def _identity(fd: int) -> tuple[int, int]:
    info = os.fstat(fd)
    return info.st_dev, info.st_ino


def _next_folder(fd: int, stuck: set[tuple[int, int, str]]) -> str | None:
    """Remove every file, link and socket of folder `fd` up to its first subfolder not in
    `stuck`; return that subfolder's name, or None once no other subfolder is left."""
    here = _identity(fd)
    with os.scandir(fd) as entries:
        for entry in entries:
            with contextlib.suppress(OSError):
                if entry.is_dir(follow_symlinks=False):
                    if (*here, entry.name) not in stuck:
                        return entry.name
                    continue
                os.unlink(entry.name, dir_fd=fd)
    return None


def _climb(fd: int, expected: tuple[int, int]) -> int | None:
    """Return a descriptor of the folder above `fd` if it is `expected`, else None."""
    parent = _open_folder("..", fd)
    if parent is not None and _identity(parent) != expected:
        os.close(parent)
        return None
    return parent


def _remove_entry(name: str, fd: int, stuck: set[tuple[int, int, str]]) -> None:
    """Remove `name` from folder `fd` (an emptied folder, or what replaced it); one that
    stays is never tried again."""
    try:
        os.rmdir(name, dir_fd=fd)
    except NotADirectoryError:
        with contextlib.suppress(OSError):
            os.unlink(name, dir_fd=fd)
    except FileNotFoundError:
        pass
    except OSError:
        stuck.add((*_identity(fd), name))


def _empty(top: int) -> bool:
    """Empty the folder `top` (the caller closes it) as far as it can; return False if a
    level was moved out of the tree meanwhile (the walk stops there)."""
    fd, names, chain = top, [], [_identity(top)]  # the levels below `top`, their identities
    stuck: set[tuple[int, int, str]] = set()  # (folder, name): cannot be opened or removed
    try:
        while True:
            name = _next_folder(fd, stuck)
            if name is not None:
                child = _open_folder(name, fd)
                if child is None:  # unreadable, gone, or a link now
                    _remove_entry(name, fd, stuck)
                    stuck.add((*_identity(fd), name))
                    continue
                if fd != top:
                    os.close(fd)
                fd = child
                names.append(name)
                chain.append(_identity(child))
                continue
            if not names:
                return True
            chain.pop()
            parent = top if len(names) == 1 else _climb(fd, chain[-1])
            if parent is None:
                return False
            if fd != top:
                os.close(fd)
            fd = parent
            _remove_entry(names.pop(), fd, stuck)
    finally:
        if fd != top:
            os.close(fd)


def remove_tree(path: str | os.PathLike[str]) -> bool:
    """Remove `path` and everything in it, whatever its depth; return whether it is gone.

    Never raises for what is inside (a file that cannot go stays, as with
    `shutil.rmtree(..., ignore_errors=True)`); a link at `path` is removed, never followed.
    """
    target = Path(path)
    try:
        parent = os.open(target.parent, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    except OSError:
        return not os.path.lexists(target)
    try:
        top = _open_folder(target.name, parent)
        if top is None:  # a file or a link: removed as such
            with contextlib.suppress(OSError):
                os.unlink(target.name, dir_fd=parent)
        else:
            try:
                emptied = _empty(top)
            finally:
                os.close(top)
            if emptied:
                with contextlib.suppress(OSError):
                    os.rmdir(target.name, dir_fd=parent)
    finally:
        os.close(parent)
    return not os.path.lexists(target)
