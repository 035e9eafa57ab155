"""Stored notebooks follow the notebook format, so JupyterLab opens them without complaint."""

from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

from course_lib.core.paths import NOTEBOOKS_DIR

NOTEBOOKS = sorted(NOTEBOOKS_DIR.glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_is_valid(path: Path) -> None:
    nbformat.validate(nbformat.read(path, as_version=4))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_stored_notebooks_hold_no_live_output(path: Path) -> None:
    """A stored 3D view or widget shows an error when reopened: only placeholders are kept."""
    from course_lib.core.files.live_outputs import is_live

    notebook = nbformat.read(path, as_version=4)

    def live_or_frame(output: dict) -> bool:
        return is_live(output) or "<iframe" in str(output.get("data", {}).get("text/html", ""))

    live = [
        n
        for n, cell in enumerate(notebook.cells)
        for o in cell.get("outputs", [])
        if live_or_frame(o)
    ]
    assert not live, f"{path.name}: live outputs stored in cells {live}; run `make notebooks`"
