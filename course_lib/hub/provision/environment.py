"""The environment every learner runs: a copy of the course built with an interpreter that
every Unix user may execute (a root-private interpreter would give them "Permission denied")."""

from __future__ import annotations

import filecmp
import os
import shutil
import stat
import subprocess
from collections.abc import Callable
from pathlib import Path

from ...core.errors import CourseError
from ...core.paths import REPO_ROOT
from ..guard.locks import LOCKS_FOLDER, hub_lock

__all__ = [
    "HUB_ONLY",
    "build_environment",
    "check_world_executable",
    "course_copy",
    "source_files",
]

# Never copied: what `make setup` builds, what learners or tests write, git's own folder.
_SKIPPED = (
    ".venv",
    ".git",
    "rosject/build",
    "rosject/install",
    "rosject/log",
    "notebooks/my_files",
    "test-artifacts",
)
# Never copied, and removed from a copy an older build made: the hub's own settings, which
# only the launcher reads (as root, from the instructor's folder). They name the accounts and
# may hold the demo's password; everything in the copy is open to every account.
HUB_ONLY = ("config/hub.yaml",)


def course_copy(environment: Path) -> Path:
    """Return where the learners' copy of the course lives inside `environment`."""
    return environment / "course"


def _skipped(relative: str) -> bool:
    parts = Path(relative).parts
    return "__pycache__" in parts or any(
        relative == s or relative.startswith(s + "/") for s in (*_SKIPPED, *HUB_ONLY)
    )


def source_files(repo: Path = REPO_ROOT) -> list[str]:
    """Return the course's files relative to `repo`: in a clone, the files git tracks (never
    an untracked one: a clone may hold secrets, and the copy is open to every learner), else
    every file outside the built and written folders; never the hub's own (HUB_ONLY)."""
    if (repo / ".git").exists() and shutil.which("git"):
        listed = (
            subprocess.run(
                ["git", "ls-files", "--cached", "-z"],
                cwd=repo,
                capture_output=True,
                check=True,
            )
            .stdout.decode()
            .split("\0")
        )
        return sorted(f for f in listed if f and not _skipped(f) and (repo / f).is_file())
    found = []
    for folder, dirs, files in os.walk(repo):
        rel_folder = os.path.relpath(folder, repo)
        dirs[:] = [d for d in dirs if not _skipped(os.path.normpath(f"{rel_folder}/{d}"))]
        found += [os.path.normpath(f"{rel_folder}/{f}") for f in files]
    return sorted(f for f in found if not _skipped(f))


def _sync(repo: Path, target: Path) -> int:
    """Copy the course's files into `target`, keeping times (make sees nothing new when nothing
    changed); return how many files were copied."""
    copied = 0
    for relative in source_files(repo):
        source, destination = repo / relative, target / relative
        if destination.exists() and filecmp.cmp(source, destination, shallow=False):
            continue
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(source, destination)
        copied += 1
    return copied


def _forget_hub_files(target: Path) -> list[str]:
    """Remove from `target` the hub's own files an older build copied there; return them."""
    removed = []
    for relative in HUB_ONLY:
        path = target / relative
        if path.is_file() or path.is_symlink():
            path.unlink()
            removed.append(relative)
    return removed


def check_world_executable(path: Path) -> None:
    """Refuse `path` unless every Unix user can reach and execute it."""
    path = Path(path)
    if not path.exists():
        raise CourseError(
            f"{path} does not exist.",
            hint="install Debian's Python (`apt-get install python3.11 python3.11-venv "
            "python3.11-dev`) or set `python:` in config/hub.yaml to one every user can run.",
        )
    for part in [*reversed(path.parents), path]:
        mode = part.stat().st_mode
        needed = stat.S_IXOTH | (stat.S_IROTH if part == path else 0)
        if mode & needed != needed:
            raise CourseError(
                f"Learners cannot execute {path}: {part} is closed to other users "
                f"(mode {stat.S_IMODE(mode):o}).",
                hint="set `python:` in config/hub.yaml to an interpreter every user can run, "
                "such as Debian's /usr/bin/python3.11.",
            )


def _open_to_all(root: Path, keep: frozenset[Path] = frozenset()) -> None:
    """Let every user read (and enter) what the build wrote, whatever root's umask was; leave
    the paths in `keep` as they are."""
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if Path(folder, d) not in keep]  # kept whole, as it is
        for name in [*dirs, *files]:
            path = Path(folder, name)
            if path.is_symlink() or path in keep:
                continue
            mode = path.stat().st_mode
            extra = stat.S_IROTH | stat.S_IRGRP
            if stat.S_ISDIR(mode) or mode & stat.S_IXUSR:
                extra |= stat.S_IXOTH | stat.S_IXGRP
            if mode & extra != extra:
                path.chmod(stat.S_IMODE(mode) | extra)
    root.chmod(0o755)


def build_environment(
    environment: Path, python: Path, *, say: Callable[[str], None] = print
) -> Path:
    """Copy the course into `environment` and run `make setup` there with `python`.

    Returns the copy's folder. A second call rebuilds only what changed (make's stamps).
    """
    check_world_executable(python)
    environment.mkdir(parents=True, exist_ok=True)
    for part in [*reversed(environment.parents), environment]:
        if part.stat().st_mode & stat.S_IXOTH == 0:
            raise CourseError(
                f"Learners cannot reach {environment}: {part} is closed to other users.",
                hint="set `environment:` in config/hub.yaml to a folder outside private homes, "
                "e.g. /opt/ros2-params-course.",
            )
    with hub_lock(environment, "build", "the build of the learners' environment", say=say):
        return _build_locked(environment, python, say)


def _build_locked(environment: Path, python: Path, say: Callable[[str], None]) -> Path:
    copy = course_copy(environment)
    if copy.resolve() != REPO_ROOT.resolve():
        copied = _sync(REPO_ROOT, copy)
        say(f"The learners' copy of the course is in {copy} ({copied} files updated).")
        for relative in _forget_hub_files(copy):
            say(f"Removed {relative} from the learners' copy: only the hub reads it, as root.")
    say(f"Building the learners' environment with {python} (`make setup`; first time: minutes).")
    result = subprocess.run(
        ["make", "--no-print-directory", "-C", str(copy), "setup", f"PYTHON={python}"],
        capture_output=True,
        text=True,
        check=False,
    )
    if result.returncode != 0:
        tail = "\n".join((result.stdout + result.stderr).strip().splitlines()[-15:])
        raise CourseError(
            f"`make setup` failed in {copy}:\n{tail}",
            hint="fix what it names (it is the same set-up as `make lab`), then retry.",
        )
    # the copy is the clone itself when the environment holds it: its hub.yaml stays closed
    kept = {copy / relative for relative in HUB_ONLY} | {environment / LOCKS_FOLDER}
    _open_to_all(environment, keep=frozenset(kept))
    return copy
