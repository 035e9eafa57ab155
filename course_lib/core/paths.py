"""Where the course's files live, derived from this package's location (any clone works)."""

from __future__ import annotations

import contextlib
import os
import stat
import sys
from pathlib import Path

from .errors import RuntimeDirError

__all__ = [
    "CONFIG_DIR",
    "CONFIG_DIR_ENV",
    "LEARNER_ROOT_ENV",
    "NOTEBOOKS_DIR",
    "PACKAGE_DIR",
    "REPO_ROOT",
    "ROSJECT_DIR",
    "SOCKET_NAME_MAX",
    "WORKSPACE_INSTALL_DIR",
    "config_dir",
    "learner_notebooks_dir",
    "runtime_dir",
    "venv_bin_dir",
]

PACKAGE_DIR = Path(__file__).resolve().parents[1]
REPO_ROOT = PACKAGE_DIR.parent
ROSJECT_DIR = REPO_ROOT / "rosject"
WORKSPACE_INSTALL_DIR = ROSJECT_DIR / "install"
CONFIG_DIR = REPO_ROOT / "config"
# Another folder of instructor YAML (`make notebooks ARGS="--config DIR"`, the tests' second
# configuration): every process of the course started with it set reads that folder instead.
CONFIG_DIR_ENV = "COURSE_CONFIG_DIR"
NOTEBOOKS_DIR = REPO_ROOT / "notebooks"
# On a class hub each learner has a copy of the notebooks in their home: this names its folder.
LEARNER_ROOT_ENV = "COURSE_LEARNER_ROOT"
SOCKET_NAME_MAX = 32  # the longest socket name in runtime_dir() ("ros2-daemon-232.sock": 20)
_SUN_PATH_MAX = 108  # bytes of a Unix socket path, its final NUL included
_POSIX_TMP = Path(os.sep, "tmp")  # where Python's tempfile goes without TMPDIR: always short


def _temp_dir() -> str:
    """Return Python's temp folder; /tmp when no variable names one (as tempfile says then,
    without importing it: the terminal's `ros2` client starts at interpreter speed)."""
    if not any(os.environ.get(v) for v in ("TMPDIR", "TEMP", "TMP")):
        return str(_POSIX_TMP)
    import tempfile

    return tempfile.gettempdir()


def _runtime_candidates() -> list[Path]:
    """Return where the runtime folder may live, best first.

    The user's XDG_RUNTIME_DIR is private by specification; a temp folder's name can be taken
    first by another user (squatted), so a folder in the user's home, which nobody else can
    create, comes last.
    """
    name = f"ros2-course-{os.getuid()}"
    found = []
    if os.environ.get("XDG_RUNTIME_DIR"):
        found.append(Path(os.environ["XDG_RUNTIME_DIR"]) / "ros2-course")
    found += [Path(_temp_dir()) / name, _POSIX_TMP / name]
    found.append(Path.home() / ".cache" / "ros2-course" / "run")
    return found


def _check_private(path: Path) -> None:
    """Refuse a runtime folder that is not a directory of this user closed to everyone else."""
    info = path.lstat()
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


def runtime_dir() -> Path:
    """Return this user's private folder for locks, markers and sockets, creating it.

    The folder is checked on every call: a directory owned by this user with no group or
    other access, else RuntimeDirError says what to do. Its path leaves room for any socket
    name of the course within the 108-byte limit of Unix socket paths, whatever TMPDIR is.
    """
    fitting = [
        c
        for c in dict.fromkeys(_runtime_candidates())
        if len(os.fsencode(c)) + 1 + SOCKET_NAME_MAX < _SUN_PATH_MAX
    ]
    refused: RuntimeDirError | None = None
    for path in fitting:
        try:
            path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
            with contextlib.suppress(FileExistsError):
                path.mkdir(mode=0o700)
            _check_private(path)
        except OSError:
            continue  # a parent folder this user cannot write: the next candidate
        except RuntimeDirError as exc:
            if path.lstat().st_uid == os.getuid() and not path.is_symlink():
                raise  # this user's own folder, left open: theirs to fix
            refused = refused or exc  # another user's (squatted): the next candidate
            continue
        return path
    raise refused or RuntimeDirError(
        "No folder for the course's locks and sockets could be made.",
        hint="set TMPDIR to a folder of your own (`mkdir -p ~/.cache/tmp && export "
        "TMPDIR=~/.cache/tmp`), then retry.",
    )


def learner_notebooks_dir() -> Path:
    """Return the folder of the learner's notebooks: the clone's, or their copy on a hub."""
    root = os.environ.get(LEARNER_ROOT_ENV)
    return Path(root) / "notebooks" if root else NOTEBOOKS_DIR


def config_dir() -> Path:
    """Return the folder of the instructor's YAML files: config/, or COURSE_CONFIG_DIR's."""
    chosen = os.environ.get(CONFIG_DIR_ENV)
    return Path(chosen).resolve() if chosen else CONFIG_DIR


def venv_bin_dir() -> Path:
    """Return the folder holding this interpreter's scripts (`ros2`, `jupyter`, ...)."""
    return Path(sys.executable).parent
