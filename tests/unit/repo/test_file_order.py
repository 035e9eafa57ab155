"""The suite deals its longest files first, from a table of measured seconds."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest
from file_order import SECONDS_FILE, longest_first, read_seconds, write_seconds
from run_suite import pytest_argv

from course_lib.core.paths import REPO_ROOT


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


def _order(nodeids: list[str], seconds: dict[str, float], **kwargs: object) -> list[str]:
    return [i.nodeid for i in longest_first([Item(n) for n in nodeids], seconds, **kwargs)]


def test_a_file_that_waits_for_the_build_starts_after_a_workers_first_file() -> None:
    seconds = {"walk.py": 200.0, "hub.py": 150.0, "b.py": 100.0, "c.py": 90.0, "d.py": 50.0}
    nodeids = ["d.py::t", "c.py::t", "hub.py::t1", "b.py::t", "walk.py::t", "hub.py::t2"]
    assert _order(nodeids, seconds, late={"hub.py"}, workers=2) == [
        "walk.py::t",
        "b.py::t",
        "hub.py::t1",
        "hub.py::t2",
        "c.py::t",
        "d.py::t",
    ]
    # two that wait: neither takes the other's place in the first round
    assert _order(nodeids, seconds, late={"hub.py", "b.py"}, workers=2)[:2] == [
        "walk.py::t",
        "c.py::t",
    ]
    # already past the first round: its place is kept
    assert _order(nodeids, seconds, late={"d.py"}, workers=2) == _order(nodeids, seconds)
    # fewer files than workers: it goes last
    assert _order(["hub.py::t", "b.py::t"], seconds, late={"hub.py"}, workers=4) == [
        "b.py::t",
        "hub.py::t",
    ]


def test_every_file_with_a_class_hub_waits_for_the_learners_environment() -> None:
    """A hub's start waits for the learners' environment build; a file that starts one without
    the marker would be dealt first and stand idle for the build (ci95: 75 s)."""
    users = ("from class_hub import", "from hub_accounts import")
    unmarked = []
    for path in sorted((REPO_ROOT / "tests").rglob("test_*.py")):
        text = path.read_text(encoding="utf-8")
        starts_a_hub = any(line.startswith(users) for line in text.splitlines())
        if starts_a_hub and "pytest.mark.learners_env" not in text:
            unmarked.append(str(path.relative_to(REPO_ROOT)))
    assert not unmarked, (
        f"files that start a class hub without @pytest.mark.learners_env: {unmarked}"
    )
