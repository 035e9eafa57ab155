"""Each stored output belongs to its own cell (`make notebooks` keys kept outputs by cell id)."""

from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

from course_lib.core.paths import NOTEBOOKS_DIR
from course_lib.tools.notebook_outputs import IGNORE_TAG, clean_notebook

NOTEBOOKS = sorted(NOTEBOOKS_DIR.glob("[0-9][0-9]_*.ipynb"))


def _result(text: str, count: int) -> nbformat.NotebookNode:
    return nbformat.v4.new_output(
        "execute_result", data={"text/plain": text}, execution_count=count
    )


def _notebook(*outputs: str) -> nbformat.NotebookNode:
    """Two live cells with the same source, with the given outputs (ids 'first', 'second')."""
    nb = nbformat.v4.new_notebook()
    for count, (cell_id, text) in enumerate(zip(("first", "second"), outputs, strict=True), 1):
        cell = nbformat.v4.new_code_cell("travel.check()", id=cell_id)
        cell.metadata["tags"] = [IGNORE_TAG]
        cell.execution_count = count
        cell.outputs = [_result(text, count)] if text else []
        nb.cells.append(cell)
    return nb


def test_cells_with_the_same_source_keep_their_own_outputs() -> None:
    old = _notebook("Attempt 1: not yet", "Attempt 2: passed!")
    new = clean_notebook(_notebook("", ""), old)
    texts = [c.outputs[0]["data"]["text/plain"] for c in new.cells]
    assert texts == ["Attempt 1: not yet", "Attempt 2: passed!"]


def test_an_edited_cell_does_not_keep_its_old_output() -> None:
    old = _notebook("Attempt 1: not yet", "Attempt 2: passed!")
    new = _notebook("", "")
    new.cells[0].source = "travel.check(verbose=True)"
    assert clean_notebook(new, old).cells[0].outputs == []


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_stored_outputs_belong_to_their_cells(path: Path) -> None:
    nb = nbformat.read(path, as_version=4)
    for index, cell in enumerate(nb.cells):
        if cell.cell_type != "code":
            continue
        for output in cell.outputs:
            if output.output_type == "execute_result":
                assert output.execution_count == cell.execution_count, (
                    f"{path.name} cell {index} ({cell.get('id')}) stores the result of "
                    f"execution {output.execution_count}, but ran as {cell.execution_count}: "
                    "re-store the notebook with `make notebooks`"
                )


def test_lesson_11_stores_each_attempt_in_its_own_cell() -> None:
    nb = nbformat.read(NOTEBOOKS_DIR / "11_beyond_the_tutorial.ipynb", as_version=4)
    checks = [c for c in nb.cells if c.cell_type == "code" and c.source == "travel.check()"]
    texts = ["".join(o["data"]["text/plain"] for o in c.outputs if "data" in o) for c in checks]
    assert len(texts) == 2
    assert texts[0].startswith("Attempt 1:") and "passed" not in texts[0], texts[0]
    assert texts[1].startswith("Attempt 2: passed!"), texts[1]


def test_a_refresh_runs_the_exercises_as_a_first_run_and_keeps_the_learners_counts(
    tmp_path: Path,
) -> None:
    from course_lib.lessons.skills.attempts import ATTEMPTS_FILE, AttemptLog
    from course_lib.tools.notebook_outputs import first_attempts

    AttemptLog(tmp_path).add("07 drive", passed=False)
    kept = (tmp_path / ATTEMPTS_FILE).read_bytes()
    with first_attempts(tmp_path):
        assert AttemptLog(tmp_path).tally("07 drive").attempts == 0
        AttemptLog(tmp_path).add("07 drive", passed=True)  # the lesson's own run
    assert (tmp_path / ATTEMPTS_FILE).read_bytes() == kept
    with first_attempts(tmp_path / "none_yet"):
        (tmp_path / "none_yet").mkdir()
        AttemptLog(tmp_path / "none_yet").add("07 drive", passed=True)
    assert not (tmp_path / "none_yet" / ATTEMPTS_FILE).exists()
