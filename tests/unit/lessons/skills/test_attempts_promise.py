"""The getting-started guide's promise about restarts says what happens to exercise attempts
(they are kept)."""

from __future__ import annotations

from pathlib import Path

from course_lib.lessons.skills.attempts import ATTEMPTS_FILE, AttemptLog

GUIDE = Path(__file__).resolve().parents[4] / "book" / "guides" / "getting-started.md"


def test_the_guide_says_attempts_outlive_a_restart_and_where_they_are_kept() -> None:
    text = " ".join(GUIDE.read_text(encoding="utf-8").split())
    assert "Restart Kernel and Run All gives the results of a first run in everything but" in text
    assert f"notebooks/my_files/{ATTEMPTS_FILE}" in text


def test_attempts_are_kept_in_the_learners_folder_across_new_logs(tmp_path: Path) -> None:
    AttemptLog(tmp_path).add("07 drive", passed=False)
    assert (tmp_path / ATTEMPTS_FILE).exists()
    assert AttemptLog(tmp_path).tally("07 drive").attempts == 1  # a restarted kernel's log
