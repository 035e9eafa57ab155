"""A lesson added as a notebook, one module and one table line starts for real: `start(12)`.

A copy of the repository with lesson 12 added (tests/support/lab/added_lesson.py, as in
tests/unit/lessons/test_adding_a_lesson.py), in a Python of its own with a real ROS session:
the lesson starts, records its run for a replay (it drives a node), and its self-check runs
through `lesson.self_check()` and passes once its file is written.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from added_lesson import add_lesson_12, copy_repository, run_in_copy

from course_lib.core.paths import REPO_ROOT

pytestmark = [pytest.mark.ros, pytest.mark.slow]

PROBE = r"""
import json, sys
from pathlib import Path

from course_lib.lessons import start
from course_lib.session.session import close_current_session

work = Path(sys.argv[1])
lesson = start(12)
out = {"title": lesson.title, "replay": type(lesson.replay).__name__, "node": lesson.replay.node}
lesson.learner_dir = work
(work / "throwaway.txt").write_text("done\n")
out["check"] = lesson.self_check().text()
lesson.replay.close()
close_current_session()
print(json.dumps(out))
"""


def test_a_lesson_added_by_the_catalogue_starts_and_checks(tmp_path: Path) -> None:
    root = tmp_path / "repo"
    copy_repository(REPO_ROOT, root)
    add_lesson_12(root)
    work = tmp_path / "work"
    work.mkdir()
    done = run_in_copy(root, PROBE, work, COURSE_LEARNER_ROOT=str(work))
    lines = done.stdout.splitlines()
    assert lines[:2] == [
        "Lesson 12 · A throwaway lesson",
        "Ready: your own ROS 2 session is running and `%ros2` works in this notebook.",
    ]
    out = json.loads(lines[-1])
    assert out["title"] == "A throwaway lesson"
    assert (out["replay"], out["node"]) == ("LessonRun", "/param_vel_node")
    assert "Everything passed (1 of 1)" in out["check"]
