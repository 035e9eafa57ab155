"""A killed lab is spoken of only by a lab of its own clone (the runtime folder is per user)."""

from __future__ import annotations

from pathlib import Path

from course_lib.core.paths import REPO_ROOT
from course_lib.lab.leftovers import ran_from_this_clone


def _files(tmp_path: Path, clone: str | None) -> list[Path]:
    domain = tmp_path / "lab-4242.domain"
    domain.write_text("17")
    if clone is None:
        return [domain]
    marker = tmp_path / "lab-4242.clone"
    marker.write_text(clone)
    return [domain, marker]


def test_a_lab_of_this_clone_is_ours(tmp_path: Path) -> None:
    assert ran_from_this_clone(_files(tmp_path, str(REPO_ROOT)))


def test_a_lab_of_another_clone_is_not(tmp_path: Path) -> None:
    assert not ran_from_this_clone(_files(tmp_path, str(tmp_path / "another-clone")))


def test_a_lab_that_names_no_clone_is_not(tmp_path: Path) -> None:
    assert not ran_from_this_clone(_files(tmp_path, None))
