"""Where `useradd --create-home` puts a new account's home (the tests that create accounts)."""

from __future__ import annotations

import subprocess
from pathlib import Path

__all__ = ["new_home"]


def new_home(name: str) -> Path:
    """Return the home folder useradd gives a new account `name` (its defaults' HOME)."""
    told = subprocess.run(["useradd", "-D"], capture_output=True, text=True, check=True).stdout
    return Path(dict(line.split("=", 1) for line in told.split())["HOME"]) / name
