"""The suite deals its longest files first, from a table of measured seconds."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest
from file_order import SECONDS_FILE, longest_first, read_seconds, write_seconds

from course_lib.core.paths import REPO_ROOT
from course_lib.tools.suite import pytest_argv


@dataclass
class Item:
    nodeid: str


def test_the_longest_file_goes_first_and_a_file_keeps_its_tests_in_order() -> None:
    items = [Item(n) for n in ("a.py::t1", "b.py::t1", "a.py::t2", "c.py::t1", "d.py::t1")]
    ordered = longest_first(items, {"c.py": 60.0, "a.py": 5.0})
    assert [i.nodeid for i in ordered] == [
        "c.py::t1",
        "a.py::t1",
        "a.py::t2",
        "b.py::t1",
        "d.py::t1",
    ]


def test_every_file_the_table_names_exists() -> None:
    """A renamed or removed test file would silently lose its place at the front."""
    missing = [name for name in read_seconds() if not (REPO_ROOT / name).is_file()]
    assert not missing, f"{SECONDS_FILE.name} names files that no longer exist: {missing}"


def test_the_table_puts_the_slowest_browser_walk_in_front() -> None:
    seconds = read_seconds()
    assert max(seconds, key=seconds.__getitem__) == "tests/browser/test_lab_full_walk.py"


def test_a_written_table_reads_back_and_leaves_out_short_files(tmp_path: Path) -> None:
    path = tmp_path / "seconds.txt"
    write_seconds({"a.py": 1.0, "b.py": 30.4, "c.py": 7.6}, path)
    assert read_seconds(path) == {"b.py": 30.0, "c.py": 8.0}


def test_a_bad_line_names_its_file_and_line(tmp_path: Path) -> None:
    path = tmp_path / "seconds.txt"
    path.write_text("# comment\n12 a.py\nslow b.py\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"seconds.txt:3: expected 'SECONDS FILE'"):
        read_seconds(path)


def test_xdist_keeps_the_order() -> None:
    """xdist's own order (most tests first) would deal the long one-test files last."""
    assert "--no-loadscope-reorder" in pytest_argv([])
