"""Stored notebooks follow the notebook format, so JupyterLab opens them without complaint."""

from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

from course_lib.paths import NOTEBOOKS_DIR

NOTEBOOKS = sorted(NOTEBOOKS_DIR.glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_is_valid(path: Path) -> None:
    nbformat.validate(nbformat.read(path, as_version=4))
