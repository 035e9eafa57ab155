"""The learners' copy of the course holds what git tracks, never a clone's untracked files nor
the hub's own settings."""

from __future__ import annotations

import subprocess
from pathlib import Path

from course_lib.hub.provision.environment import source_files


def test_an_untracked_file_of_the_clone_is_never_copied_for_the_learners(tmp_path: Path) -> None:
    def git(*argv: str) -> None:
        subprocess.run(["git", *argv], cwd=tmp_path, check=True, capture_output=True)

    git("init", "-q")
    (tmp_path / "course.py").write_text("print('course')\n")
    git("add", "course.py")
    (tmp_path / "secrets.env").write_text("TOKEN=do-not-share\n")  # neither added nor ignored
    assert source_files(tmp_path) == ["course.py"]


def test_the_hubs_own_settings_are_never_copied_for_the_learners(tmp_path: Path) -> None:
    """config/hub.yaml is tracked, and an instructor puts the demo's password there: the copy
    is open to every account, and their labs do not read it."""
    (tmp_path / "config").mkdir()
    for name in ("course.yaml", "hub.yaml"):
        (tmp_path / "config" / name).write_text("shared_password: do-not-share\n")
    assert source_files(tmp_path) == ["config/course.yaml"]  # not a clone: every file
    subprocess.run(["git", "init", "-q"], cwd=tmp_path, check=True, capture_output=True)
    subprocess.run(["git", "add", "config"], cwd=tmp_path, check=True, capture_output=True)
    assert source_files(tmp_path) == ["config/course.yaml"]
