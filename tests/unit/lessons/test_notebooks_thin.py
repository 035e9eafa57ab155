"""Every lesson notebook stays thin: prose plus a few short calls into course_lib (no def,
class, `import rclpy` or sleeps in lesson cells)."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

from course_lib.core.paths import NOTEBOOKS_DIR
from course_lib.lessons.catalogue import LESSONS

MAX_LINES = 6
NOTEBOOKS = sorted(NOTEBOOKS_DIR.glob("[0-9][0-9]_*.ipynb"))


def _code_cells(path: Path) -> list[tuple[int, list[str], str]]:
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    return [
        (i, c.get("metadata", {}).get("tags", []), "".join(c["source"]))
        for i, c in enumerate(cells)
        if c["cell_type"] == "code"
    ]


def fat_reasons(source: str, tags: list[str]) -> list[str]:
    """Return why a cell is too fat for a lesson notebook (empty: it is fine)."""
    if source.lstrip().startswith("%%"):
        return []  # a cell magic: its body is `ros2` command lines, not Python
    python = "\n".join("" if ln.lstrip().startswith("%") else ln for ln in source.splitlines())
    lines = [ln for ln in python.splitlines() if ln.strip() and not ln.strip().startswith("#")]
    reasons = [f"{len(lines)} lines of code (max {MAX_LINES})"] if len(lines) > MAX_LINES else []
    tree = ast.parse(python)
    for node in ast.walk(tree):
        defines = isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
        if defines and "exercise" not in tags:
            reasons.append(f"defines {node.name} outside an exercise cell")
        if isinstance(node, ast.Import) and any(
            a.name.split(".")[0] == "rclpy" for a in node.names
        ):
            reasons.append("imports rclpy")
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "rclpy":
            reasons.append("imports rclpy")
        if isinstance(node, ast.Attribute) and node.attr == "sleep":
            reasons.append("sleeps")
        if isinstance(node, ast.Name) and node.id == "sleep":
            reasons.append("sleeps")
        if isinstance(node, ast.Attribute) and node.attr in ("environ", "putenv"):
            reasons.append("sets up the environment")
    return reasons


def test_the_notebooks_are_the_catalogues_lessons() -> None:
    assert [p.name for p in NOTEBOOKS] == [spec.notebook for spec in LESSONS]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_cells_are_thin(path: Path) -> None:
    fat = [
        f"cell {i}: {', '.join(reasons)}"
        for i, tags, source in _code_cells(path)
        if (reasons := fat_reasons(source, tags))
    ]
    assert not fat, f"{path.name} has fat cells:\n" + "\n".join(fat)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_first_cell_starts_the_lesson_and_last_is_the_self_check(path: Path) -> None:
    cells = _code_cells(path)
    number = int(path.name[:2])
    assert cells[0][2] == f"from course_lib.lessons import start\n\nlesson = start({number})"
    assert cells[-1][2] == "lesson.self_check()"
    assert "nbval-check-output" in cells[-1][1]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_every_code_cell_says_whether_nbval_checks_it(path: Path) -> None:
    for i, tags, _source in _code_cells(path):
        assert {"nbval-check-output", "nbval-ignore-output"} & set(tags), f"cell {i} untagged"


@pytest.mark.parametrize(
    ("source", "tags", "why"),
    [
        ("def f():\n    return 1", [], "defines f outside an exercise cell"),
        ("import rclpy", [], "imports rclpy"),
        ("import time\ntime.sleep(1)", [], "sleeps"),
        ("import os\nos.environ['ROS_DOMAIN_ID'] = '3'", [], "sets up the environment"),
        ("\n".join(f"x{i} = {i}" for i in range(9)), [], "9 lines of code (max 6)"),
    ],
)
def test_fat_cells_are_caught(source: str, tags: list[str], why: str) -> None:
    assert why in fat_reasons(source, tags)


def test_exercise_cells_may_define_functions_and_magics_are_fine() -> None:
    assert fat_reasons("def helper():\n    return 0.2", ["exercise"]) == []
    assert fat_reasons("%%ros2\nparam set /n velocity 0.2", []) == []
    assert fat_reasons("%ros2 param list", []) == []
