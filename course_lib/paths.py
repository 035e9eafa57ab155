"""Where the course's files live, derived from this package's location (any clone works)."""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

__all__ = [
    "CONFIG_DIR",
    "NOTEBOOKS_DIR",
    "PACKAGE_DIR",
    "REPO_ROOT",
    "ROSJECT_DIR",
    "WORKSPACE_INSTALL_DIR",
    "runtime_dir",
    "venv_bin_dir",
]

PACKAGE_DIR = Path(__file__).resolve().parent
REPO_ROOT = PACKAGE_DIR.parent
ROSJECT_DIR = REPO_ROOT / "rosject"
WORKSPACE_INSTALL_DIR = ROSJECT_DIR / "install"
CONFIG_DIR = REPO_ROOT / "config"
NOTEBOOKS_DIR = REPO_ROOT / "notebooks"


def runtime_dir() -> Path:
    """Return this user's private folder for locks and sockets, creating it."""
    path = Path(tempfile.gettempdir()) / f"ros2-course-{os.getuid()}"
    path.mkdir(mode=0o700, exist_ok=True)
    return path


def venv_bin_dir() -> Path:
    """Return the folder holding this interpreter's scripts (`ros2`, `jupyter`, ...)."""
    return Path(sys.executable).parent
