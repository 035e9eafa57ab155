"""Adding a lesson is its notebook, one module and one line in the catalogue's table.

A copy of the repository's course_lib (with config/ and notebooks/) gets a throwaway lesson
12 by exactly those three edits; a Python that imports the copy then shows that everything
that lists lessons knows lesson 12, through the real code paths: the progress record and
store take it, the instructor's page shows it with its title, `lesson.self_check()` runs its
check through `run_checks`, its templated cell renders, its replay knows the node it drives,
and `start(N)` counts it. (`start(12)` itself needs a ROS session: tests/integration/lessons/
test_adding_a_lesson_starts.py starts it for real.)
"""

from __future__ import annotations

import difflib
import json
from pathlib import Path

from added_lesson import MODULE, NOTEBOOK, TABLE, add_lesson_12, copy_repository, run_in_copy

from course_lib.core.paths import REPO_ROOT
from course_lib.lessons.settings import load_course_settings

# What the copy is asked, in a Python of its own (its course_lib first on the path).
PROBE = r"""
import json, sys
from pathlib import Path

import nbformat

from course_lib.hub.progress.page import render_page
from course_lib.hub.progress.store import ProgressStore
from course_lib.lessons import start
from course_lib.lessons.catalogue import TITLES
from course_lib.lessons.lesson import Lesson
from course_lib.lessons.progress.record import EXERCISES, parse_record
from course_lib.lessons.replay import DRIVEN_NODES
from course_lib.lessons.settings import load_course_settings
from course_lib.lessons.texts import render_cells

work = Path(sys.argv[1])
out = {}
record = {"user": "ada", "lesson": 12, "passed": False, "failed": "not yet"}
attempt = {**record, "passed": True, "failed": "", "exercise": "12 throwaway", "attempt": 1}
store = ProgressStore(work / "progress.sqlite")
for body in (record, attempt):
    store.add(parse_record(json.dumps(body).encode()))
out["stored"] = [(s.user, s.lesson, s.passed) for s in store.states()]
out["exercises"] = EXERCISES.get("12 throwaway")
out["page"] = render_page(["ada"], store.states(), titles=TITLES, exercises=store.exercise_stats())
settings = load_course_settings()
lesson = Lesson(12, None, settings)
lesson.learner_dir = work
out["before"] = lesson.self_check().text()
(work / "throwaway.txt").write_text("done\n")
out["after"] = lesson.self_check().text()
nb = nbformat.read(Path("notebooks/12_throwaway.ipynb"), as_version=4)
out["rendered"] = [render_cells("12_throwaway.ipynb", nb, settings), nb.cells[2].source]
out["driven"] = DRIVEN_NODES.get(12)
try:
    start(13)
except ValueError as error:
    out["start"] = str(error)
print(json.dumps(out))
"""


def _changed(before: Path, after: Path) -> tuple[set[str], list[str]]:
    """Return the files only `after` has, and the lines its table adds to `before`'s."""

    def files(root: Path) -> set[str]:
        found = (p.relative_to(root).as_posix() for p in root.rglob("*") if p.is_file())
        return {f for f in found if "__pycache__" not in f}

    new = files(after) - files(before)
    diff = difflib.unified_diff(
        (before / TABLE).read_text().splitlines(), (after / TABLE).read_text().splitlines(), n=0
    )
    lines = [ln for ln in diff if ln[:1] in "+-" and ln[:3] not in ("+++", "---")]
    return new, lines


def test_a_new_lesson_is_a_notebook_a_module_and_a_table_line(tmp_path: Path) -> None:
    root = tmp_path / "repo"
    copy_repository(REPO_ROOT, root)
    add_lesson_12(root)
    new, table_lines = _changed(REPO_ROOT, root)
    assert new == {NOTEBOOK.as_posix(), MODULE.as_posix()}
    assert table_lines == ['+    "l12_throwaway",']
    work = tmp_path / "work"
    work.mkdir()
    done = run_in_copy(root, PROBE, work)
    out = json.loads(done.stdout.splitlines()[-1])
    assert out["stored"] == [["ada", 12, False]]
    assert out["exercises"] == 12
    page = out["page"]
    assert '<th title="A throwaway lesson">12<br><small>A throwaway lesson</small></th>' in page
    assert '<td class="failed" title="not yet">' in page and "12 throwaway" in page
    assert out["before"].splitlines()[:2] == [
        "Self-check, lesson 12",
        "  ✗ not yet: you wrote my_files/throwaway.txt",
    ]
    assert "Everything passed (1 of 1)" in out["after"]
    speed = load_course_settings(root / "config" / "course.yaml").default_velocity_mps
    assert out["rendered"] == [["e12a0001"], f"Drive at {speed:g} m/s."]
    assert out["driven"] == "/param_vel_node"
    assert out["start"] == "there are lessons 1 to 12, not 13"
