"""A throwaway lesson 12 added to a copy of the repository as the catalogue says a lesson is
added: its notebook, one module in course_lib/lessons/catalogue/ and one line in the table."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

__all__ = ["MODULE", "NOTEBOOK", "TABLE", "add_lesson_12", "copy_repository", "run_in_copy"]

TABLE = Path("course_lib/lessons/catalogue/__init__.py")
MODULE = Path("course_lib/lessons/catalogue/l12_throwaway.py")
NOTEBOOK = Path("notebooks/12_throwaway.ipynb")
LAST_LINE = '    "l11_beyond_the_tutorial",\n'

MODULE_TEXT = '''"""Lesson 12, a throwaway: its self-check, one templated cell and its SPEC."""

from __future__ import annotations

from ...config.course import CourseSettings
from .spec import Check, LessonSpec, LessonView, check


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 12's check: the learner wrote my_files/throwaway.txt."""
    done = lesson.learner_file("throwaway.txt").exists()
    return [check("you wrote my_files/throwaway.txt", done, "run the cell that writes it.")]


def _prose(s: CourseSettings) -> str:
    return f"Drive at {s.default_velocity_mps:g} m/s."


SPEC = LessonSpec(
    12,
    "12_throwaway.ipynb",
    "A throwaway lesson",
    self_check,
    driven_node="/param_vel_node",
    exercises=("12 throwaway",),
    templates={"e12a0001": _prose},
    settings=("default_velocity_mps",),
)
'''


def _cell(kind: str, cell_id: str, source: str) -> dict:
    cell = {"cell_type": kind, "id": cell_id, "metadata": {}, "source": source}
    return {**cell, "execution_count": None, "outputs": []} if kind == "code" else cell


NOTEBOOK_JSON = {
    "cells": [
        _cell("markdown", "e12a0000", "# Lesson 12: a throwaway"),
        _cell("code", "e12a0002", "from course_lib.lessons import start\n\nlesson = start(12)"),
        _cell("markdown", "e12a0001", "Drive at some speed."),
        _cell("code", "e12a0003", "lesson.self_check()"),
    ],
    "metadata": {},
    "nbformat": 4,
    "nbformat_minor": 5,
}


def add_lesson_12(root: Path) -> None:
    """Add lesson 12 to the repository copy at `root`: a notebook, a module, a table line."""
    (root / NOTEBOOK).write_text(json.dumps(NOTEBOOK_JSON, indent=1), encoding="utf-8")
    (root / MODULE).write_text(MODULE_TEXT, encoding="utf-8")
    table = (root / TABLE).read_text(encoding="utf-8")
    assert table.count(LAST_LINE) == 1, "the table's last line moved: update this test"
    table = table.replace(LAST_LINE, LAST_LINE + '    "l12_throwaway",\n')
    (root / TABLE).write_text(table, encoding="utf-8")


def copy_repository(source: Path, root: Path) -> None:
    """Copy what a lesson needs of the repository at `source` (code, config, notebooks)."""
    ignore = shutil.ignore_patterns("__pycache__", "my_files", ".ipynb_checkpoints")
    for folder in ("course_lib", "config", "notebooks"):
        shutil.copytree(source / folder, root / folder, ignore=ignore)


def run_in_copy(
    root: Path, probe: str, work: Path, **env: str
) -> subprocess.CompletedProcess[str]:
    """Run the Python `probe` (argv[1]: `work`) on the copy at `root`, none of this process's
    course settings inherited; fail the test with its stderr if it fails."""
    keep = {k: v for k, v in os.environ.items() if not k.startswith(("COURSE_", "PYTHONPATH"))}
    done = subprocess.run(
        [sys.executable, "-c", probe, str(work)],
        cwd=root,
        env={**keep, "PYTHONPATH": str(root), **env},
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done
