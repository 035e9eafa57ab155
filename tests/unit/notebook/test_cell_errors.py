"""cell_errors' hints, on a notebook of our own: a name its cells define, a name they do not,
`%ros2` before the first cell, and no notebook at all (nbval, a plain kernel)."""

from __future__ import annotations

import json
from pathlib import Path

from course_lib.notebook.cell_errors import defining_cell, hint_for


def _notebook(folder: Path) -> Path:
    cells = [
        "from course_lib.lessons import start\n\nlesson = start(7)",
        "%ros2 run parameter_tests param_vel",
        "plot = lesson.speed_plot()",
        "%%writefile my_files/x.yaml\nnot: python",
        "for speed in (0.1, 0.2):\n    total = speed",
    ]
    path = folder / "07_move_the_robot.ipynb"
    notebook = {"cells": [{"cell_type": "code", "source": c} for c in cells]}
    path.write_text(json.dumps(notebook), encoding="utf-8")
    return path


def test_the_cell_that_defines_a_name_is_found(tmp_path: Path) -> None:
    notebook = _notebook(tmp_path)
    assert defining_cell(notebook, "lesson") == "lesson = start(7)"
    assert defining_cell(notebook, "start") == "from course_lib.lessons import start"
    assert defining_cell(notebook, "plot") == "plot = lesson.speed_plot()"
    assert defining_cell(notebook, "total") == "total = speed"
    assert defining_cell(notebook, "speed") == "for speed in (0.1, 0.2):"
    assert defining_cell(notebook, "nowhere") is None


def test_a_lesson_name_gets_its_hint_and_another_name_none(tmp_path: Path) -> None:
    notebook = _notebook(tmp_path)
    hint = hint_for(NameError("name 'plot' is not defined", name="plot"), notebook)
    assert hint is not None and "`plot = lesson.speed_plot()`" in hint
    assert "`lesson = start(7)`" in hint
    assert hint_for(NameError("x", name="typo"), notebook) is None
    assert hint_for(ValueError("plot"), notebook) is None


def test_ros2_before_the_first_cell_gets_its_hint(tmp_path: Path) -> None:
    from IPython.core.error import UsageError

    error = UsageError("Line magic function `%ros2` not found.")
    hint = hint_for(error, _notebook(tmp_path))
    assert hint is not None and "`lesson = start(7)`" in hint
    assert hint_for(UsageError("Line magic function `%ros3` not found."), tmp_path) is None


def test_no_notebook_no_hint() -> None:
    assert hint_for(NameError("x", name="lesson"), None) is None
    assert hint_for(NameError("x", name="lesson"), Path("/nonexistent.ipynb")) is None
