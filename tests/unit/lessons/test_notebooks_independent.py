"""Lessons never rewrite the repository's files and never read another lesson's files.

`make test` runs the notebooks in parallel, in any order: a lesson may only read files in git
and files it writes itself (in notebooks/my_files/, which git ignores).
"""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

from course_lib.core.paths import NOTEBOOKS_DIR

NOTEBOOKS = sorted(NOTEBOOKS_DIR.glob("[0-9][0-9]_*.ipynb"))
LEARNER = "my_files/"
PANEL_DEFAULT = "panel_params.yaml"  # Lesson.parameter_panel(save_as=...)


def _python(path: Path) -> list[ast.Module]:
    trees = []
    for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
        source = "".join(cell["source"])
        if cell["cell_type"] != "code" or source.lstrip().startswith("%%"):
            continue
        lines = ["" if ln.lstrip().startswith("%") else ln for ln in source.splitlines()]
        trees.append(ast.parse("\n".join(lines)))
    return trees


def _text(node: ast.AST | None) -> str | None:
    return node.value if isinstance(node, ast.Constant) and isinstance(node.value, str) else None


def _argument(call: ast.Call, index: int, keyword: str) -> ast.AST | None:
    if len(call.args) > index:
        return call.args[index]
    return next((k.value for k in call.keywords if k.arg == keyword), None)


def file_use(path: Path) -> tuple[set[str], set[str]]:
    """Return (files the notebook writes, files it names) as it spells them."""
    writes, names = set(), set()
    for tree in _python(path):
        for node in ast.walk(tree):
            text = _text(node)
            if text and (text.startswith(LEARNER) or text.startswith("../")):
                names.add(text)
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
                continue
            method = node.func.attr
            if method == "ros2_to_file":
                writes.add(_text(_argument(node, 1, "path")) or "?")
            elif method == "edit_file":
                target = _text(_argument(node, 0, "path"))
                if target is not None:  # else a variable holding a copy_file() result
                    writes.add(target)
            elif method == "copy_file":
                writes.add(LEARNER + (_text(_argument(node, 1, "name")) or "?"))
            elif method == "parameter_panel":
                writes.add(LEARNER + (_text(_argument(node, 1, "save_as")) or PANEL_DEFAULT))
    return writes, names


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_lesson_writes_only_learner_files(path: Path) -> None:
    writes, _names = file_use(path)
    outside = sorted(w for w in writes if not w.startswith(LEARNER))
    assert not outside, f"{path.name} writes {outside}: write into {LEARNER} instead"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_lesson_reads_no_other_lessons_files(path: Path) -> None:
    writes, names = file_use(path)
    others = {w: p.name for p in NOTEBOOKS if p != path for w in file_use(p)[0]}
    shared = sorted(f"{n} (written by {others[n]})" for n in names | writes if n in others)
    assert not shared, f"{path.name} depends on another lesson's run: {shared}"


def test_the_rules_see_a_rewrite_of_a_tracked_file(tmp_path: Path) -> None:
    cell = 'lesson.ros2_to_file("param dump /n", "../rosject/p/config/n.yaml")'
    notebook = {"cells": [{"cell_type": "code", "source": [cell], "metadata": {}}]}
    path = tmp_path / "99_x.ipynb"
    path.write_text(json.dumps(notebook))
    assert file_use(path)[0] == {"../rosject/p/config/n.yaml"}
