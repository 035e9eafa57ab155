"""This user's private folder for the course's locks, markers and sockets, checked on each use.

It imports only `os` and `stat` (and the course's errors, which import nothing): the
terminal's `ros2` client (course_lib.ros2.command.quick) finds its daemon's socket here at
interpreter speed, so paths are strings; `core.paths.runtime_dir()` gives the same folder as a
Path.
"""

from __future__ import annotations

import os
import stat

from .errors import RuntimeDirError

__all__ = ["SOCKET_NAME_MAX", "runtime_folder"]

SOCKET_NAME_MAX = 32  # the longest socket name in the folder ("ros2-daemon-232.sock": 20)
_SUN_PATH_MAX = 108  # bytes of a Unix socket path, its final NUL included
_POSIX_TMP = os.path.join(os.sep, "tmp")  # where Python's tempfile goes without TMPDIR


def _temp_dir() -> str:
    """Return Python's temp folder; /tmp when no variable names one (as tempfile says then,
    without importing it)."""
    if not any(os.environ.get(v) for v in ("TMPDIR", "TEMP", "TMP")):
        return _POSIX_TMP
    import tempfile

    return tempfile.gettempdir()


def _candidates() -> list[str]:
    """Return where the runtime folder may live, best first.

    The user's XDG_RUNTIME_DIR is private by specification; a temp folder's name can be taken
    first by another user (squatted), so a folder in the user's home, which nobody else can
    create, comes last.
    """
    name = f"ros2-course-{os.getuid()}"
    found = []
    if os.environ.get("XDG_RUNTIME_DIR"):
        found.append(os.path.join(os.environ["XDG_RUNTIME_DIR"], "ros2-course"))
    found += [os.path.join(_temp_dir(), name), os.path.join(_POSIX_TMP, name)]
    found.append(os.path.join(os.path.expanduser("~"), ".cache", "ros2-course", "run"))
    return [os.path.normpath(path) for path in found]


def _check_private(path: str) -> None:
    """Refuse a runtime folder that is not a directory of this user closed to everyone else."""
    info = os.lstat(path)
    if not stat.S_ISDIR(info.st_mode):
        raise RuntimeDirError(
            f"The course's runtime folder {path} is not a folder (a file or a link is there).",
            hint=f"remove it (`rm {path}`), then retry.",
        )
    if info.st_uid != os.getuid():
        raise RuntimeDirError(
            f"The course's runtime folder {path} belongs to another user (uid {info.st_uid}),"
            " who could see or replace this course's locks and sockets.",
            hint=f"ask that user or an administrator to remove {path}, or set TMPDIR to a "
            "folder of your own (`export TMPDIR=$HOME/.cache/tmp` after creating it).",
        )
    if info.st_mode & 0o077:
        raise RuntimeDirError(
            f"The course's runtime folder {path} is open to other users "
            f"(mode {stat.S_IMODE(info.st_mode):o}); its sockets must be private.",
            hint=f"make it private with `chmod 700 {path}`, then retry.",
        )


def runtime_folder() -> str:
    """Return this user's private folder for locks, markers and sockets, creating it.

    The folder is checked on every call: a directory owned by this user with no group or
    other access, else RuntimeDirError says what to do. Its path leaves room for any socket
    name of the course within the 108-byte limit of Unix socket paths, whatever TMPDIR is.
    """
    fitting = [
        c
        for c in dict.fromkeys(_candidates())
        if len(os.fsencode(c)) + 1 + SOCKET_NAME_MAX < _SUN_PATH_MAX
    ]
    refused: RuntimeDirError | None = None
    for path in fitting:
        try:
            os.makedirs(os.path.dirname(path), mode=0o700, exist_ok=True)
            try:  # noqa: SIM105 (contextlib is one more import for the terminal's client)
                os.mkdir(path, 0o700)
            except FileExistsError:
                pass
            _check_private(path)
        except OSError:
            continue  # a parent folder this user cannot write: the next candidate
        except RuntimeDirError as exc:
            if os.lstat(path).st_uid == os.getuid() and not os.path.islink(path):
                raise  # this user's own folder, left open: theirs to fix
            refused = refused or exc  # another user's (squatted): the next candidate
            continue
        return path
    raise refused or RuntimeDirError(
        "No folder for the course's locks and sockets could be made.",
        hint="set TMPDIR to a folder of your own (`mkdir -p ~/.cache/tmp && export "
        "TMPDIR=~/.cache/tmp`), then retry.",
    )
