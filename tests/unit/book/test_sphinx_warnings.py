"""The book's Sphinx run reports every warning (a build with one is not ok): a broken
cross-reference is caught, a clean page gives none."""

from __future__ import annotations

from pathlib import Path

from course_lib.book.build import run_sphinx


def _source(folder: Path, page: str) -> Path:
    folder.mkdir()
    (folder / "conf.py").write_text('extensions = ["myst_parser"]\n', encoding="utf-8")
    (folder / "index.md").write_text(page, encoding="utf-8")
    return folder


def test_a_clean_page_gives_no_warning(tmp_path: Path) -> None:
    src = _source(tmp_path / "src", "# Title\n\nA [link](#title).\n")
    assert run_sphinx(src, tmp_path / "site", tmp_path / "doctrees") == ""


def test_a_link_to_a_missing_page_is_a_warning(tmp_path: Path) -> None:
    src = _source(tmp_path / "src", "# Title\n\nA [link](nowhere.md).\n")
    said = run_sphinx(src, tmp_path / "site", tmp_path / "doctrees")
    assert "nowhere" in said and "WARNING" in said, said
