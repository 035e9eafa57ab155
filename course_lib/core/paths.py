"""Where the course's files live, derived from this package's location (any clone works), and
the one way to edit a search-path variable that points at them (PATH, AMENT_PREFIX_PATH, ...:
`a:b:c` lists)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

from .runtime_folder import SOCKET_NAME_MAX, runtime_folder

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
    "append_once",
    "config_dir",
    "learner_notebooks_dir",
    "prepend",
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


def runtime_dir() -> Path:
    """Return this user's private folder for locks, markers and sockets, creating it (checked
    on every call: see core.runtime_folder)."""
    return Path(runtime_folder())


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


def _parts(existing: str | None) -> list[str]:
    return [p for p in (existing or "").split(os.pathsep) if p]


def prepend(value: str, existing: str | None) -> str:
    """Return `existing` with `value` first (moved there if already listed), empties dropped."""
    return os.pathsep.join([value, *(p for p in _parts(existing) if p != value)])


def append_once(value: str, existing: str | None) -> str:
    """Return `existing` with `value` last, unless it is listed already (then it stays put).

    The course's workspace is the learner's underlay: a workspace sourced after it comes
    first in the caller's paths and must keep winning, as in a sourced shell.
    """
    parts = _parts(existing)
    return os.pathsep.join(parts if value in parts else [*parts, value])
