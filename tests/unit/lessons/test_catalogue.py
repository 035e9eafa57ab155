"""The lesson catalogue (course_lib/lessons/catalogue) is the notebooks' own list.

Every `notebooks/NN_*.ipynb` has a row with its number and file name, its first code cell
calls `start(NN)`, and no row names a notebook that is not there; what a row says of its
notebook (templated cells, the world) is what the notebook does.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from course_lib.core.paths import NOTEBOOKS_DIR
from course_lib.lessons.catalogue import LESSONS, NUMBERS, TITLES, LessonSpec, lesson_spec

NOTEBOOKS = sorted(NOTEBOOKS_DIR.glob("[0-9][0-9]_*.ipynb"))
START = re.compile(r"\bstart\((\d+)\)")


def _cells(path: Path) -> list[dict]:
    return json.loads(path.read_text(encoding="utf-8"))["cells"]


def _code(path: Path) -> list[str]:
    return ["".join(c["source"]) for c in _cells(path) if c["cell_type"] == "code"]


def test_every_notebook_has_its_row_and_every_row_its_notebook() -> None:
    assert [p.name for p in NOTEBOOKS] == [spec.notebook for spec in LESSONS]
    assert [int(p.name[:2]) for p in NOTEBOOKS] == list(NUMBERS)
    assert len(set(NUMBERS)) == len(NUMBERS)


@pytest.mark.parametrize("spec", LESSONS, ids=lambda s: s.notebook)
def test_a_notebooks_first_code_cell_starts_its_lesson(spec: LessonSpec) -> None:
    first = _code(NOTEBOOKS_DIR / spec.notebook)[0]
    assert [int(n) for n in START.findall(first)] == [spec.number], first


@pytest.mark.parametrize("spec", LESSONS, ids=lambda s: s.notebook)
def test_a_rows_cells_and_world_are_its_notebooks(spec: LessonSpec) -> None:
    path = NOTEBOOKS_DIR / spec.notebook
    ids = {c.get("id") for c in _cells(path)}
    assert set(spec.templates) <= ids, "a templated cell the notebook does not have"
    starts_world = any("lesson.world(" in source for source in _code(path))
    assert spec.world == starts_world
    assert spec.title and TITLES[spec.number] == spec.title
    assert all(name.startswith(f"{spec.number:02d} ") for name in spec.exercises)


def test_a_lesson_that_is_not_there_is_named_with_the_ones_that_are() -> None:
    assert lesson_spec(7).notebook == "07_move_the_robot.ipynb"
    with pytest.raises(ValueError, match=f"there are lessons 1 to {NUMBERS[-1]}, not 99"):
        lesson_spec(99)


def test_the_table_imports_neither_rclpy_nor_mujoco() -> None:
    """The hub's progress service imports the table (through the progress record)."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "import course_lib.lessons.progress.record, course_lib.hub.progress.page\n"
        "heavy = [m for m in sys.modules if m.split('.')[0] in ('rclpy', 'mujoco', 'IPython')]\n"
        "print(heavy)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
