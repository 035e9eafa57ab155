"""Find the system chromium the browser tests drive (Playwright never downloads one here)."""

from __future__ import annotations

import os
import shutil

__all__ = ["INSTALL_HINT", "find_chromium"]

# Debian calls it chromium, Ubuntu's deb chromium-browser; CHROMIUM names another one.
NAMES = ("chromium", "chromium-browser")
INSTALL_HINT = (
    "browser tests need a chromium on PATH (or CHROMIUM=/path/to/chromium): "
    "`sudo apt-get install chromium` enables them (.ci/run installs it)"
)


def find_chromium(path: str | None = None) -> str | None:
    """Return the chromium to drive: $CHROMIUM if set, else the first of NAMES on `path`."""
    explicit = os.environ.get("CHROMIUM")
    if explicit:
        return shutil.which(explicit, path=path)
    for name in NAMES:
        found = shutil.which(name, path=path)
        if found:
            return found
    return None
