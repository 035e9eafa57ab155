"""A learner's own copy of the notebooks: made once, theirs afterwards, new lessons added."""

from __future__ import annotations

from pathlib import Path

from course_lib.core.paths import NOTEBOOKS_DIR, ROSJECT_DIR
from course_lib.hub.singleuser import LEARNER_FOLDER, prepare_learner_copy


def test_first_start_copies_every_lesson_and_links_the_workspace(tmp_path: Path) -> None:
    root = prepare_learner_copy(tmp_path)
    assert root == tmp_path / LEARNER_FOLDER
    lessons = sorted(p.name for p in NOTEBOOKS_DIR.glob("*.ipynb"))
    assert sorted(p.name for p in (root / "notebooks").glob("*.ipynb")) == lessons
    assert (root / "notebooks" / "my_files").is_dir()
    assert (root / "rosject").resolve() == ROSJECT_DIR.resolve()


def test_a_restart_keeps_the_learners_edits_and_files_and_adds_missing_lessons(
    tmp_path: Path,
) -> None:
    root = prepare_learner_copy(tmp_path)
    edited = root / "notebooks" / "07_move_the_robot.ipynb"
    edited.write_text('{"edited": true}', encoding="utf-8")
    mine = root / "notebooks" / "my_files" / "mine.yaml"
    mine.write_text("x: 1\n", encoding="utf-8")
    (root / "notebooks" / "03_the_simulation.ipynb").unlink()
    prepare_learner_copy(tmp_path)
    assert edited.read_text(encoding="utf-8") == '{"edited": true}'
    assert mine.read_text(encoding="utf-8") == "x: 1\n"
    assert (root / "notebooks" / "03_the_simulation.ipynb").exists()
