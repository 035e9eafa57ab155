"""book/guides/mistakes.md, the catalogue of learners' mistakes: every row names at least one test,
and every test it names exists (a `def test_...` in the named file)."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import pytest

from course_lib.core.paths import REPO_ROOT

CATALOGUE = REPO_ROOT / "book" / "guides" / "mistakes.md"
NODE_ID = re.compile(r"(tests/[\w/]+\.py)::(\w+)(\[[^\]|]*\])?")
PACED = "## Lesson 7 and 11: measuring at a person's pace"


@dataclass(frozen=True)
class Row:
    """One row of a lesson's table: its section, its line, its cells."""

    section: str
    line: int
    cells: tuple[str, ...]


def catalogue_rows(text: str) -> list[Row]:
    """Return the body rows of every table (header and separator rows left out)."""
    rows: list[Row] = []
    section, header_seen = "", False
    for number, line in enumerate(text.splitlines(), 1):
        if line.startswith("## "):
            section, header_seen = line, False
        if not line.startswith("|"):
            continue
        cells = tuple(c.strip() for c in line.strip().strip("|").split("|"))
        if not header_seen:
            header_seen = True  # the header row
        elif not set("".join(cells)) <= set("-: "):
            rows.append(Row(section, number, cells))
    return rows


def defined_tests(path: Path) -> set[str]:
    """Return the names of the test functions a file defines."""
    source = path.read_text(encoding="utf-8")
    return set(re.findall(r"^(?:async )?def (test_\w+)\(", source, re.MULTILINE))


def missing_tests(rows: list[Row], root: Path) -> list[str]:
    """Return `line: node id` for every named test whose file or function is not there."""
    missing = []
    for row in rows:
        for path, name, _params in NODE_ID.findall(row.cells[-1]):
            file = root / path
            if not file.is_file() or name not in defined_tests(file):
                missing.append(f"{row.line}: {path}::{name}")
    return missing


def rows_without_a_test(rows: list[Row]) -> list[int]:
    """Return the lines of the rows whose last cell names no test."""
    return [row.line for row in rows if not NODE_ID.search(row.cells[-1])]


def test_every_row_names_a_test() -> None:
    rows = catalogue_rows(CATALOGUE.read_text(encoding="utf-8"))
    assert len(rows) >= 40, "the catalogue's tables were not read"
    assert rows_without_a_test(rows) == []


def test_every_named_test_exists() -> None:
    rows = catalogue_rows(CATALOGUE.read_text(encoding="utf-8"))
    assert missing_tests(rows, REPO_ROOT) == []


def test_every_row_has_four_cells_and_the_paced_section_is_there() -> None:
    text = CATALOGUE.read_text(encoding="utf-8")
    assert PACED in text.splitlines()
    rows = catalogue_rows(text)
    assert [r.line for r in rows if len(r.cells) != 4] == []
    assert {r.section for r in rows} >= {"## Lesson 7: move the robot with a parameter"}


@pytest.mark.parametrize(
    ("body", "without", "missing"),
    [
        ("| a | b | c | none |", [3], []),
        ("| a | b | c | tests/unit/x.py::test_gone |", [], ["3: tests/unit/x.py::test_gone"]),
        ("| a | b | c | tests/unit/x.py::test_here[one] |", [], []),
        ("| a | b | c | tests/nope.py::test_here |", [], ["3: tests/nope.py::test_here"]),
    ],
)
def test_a_row_without_a_test_or_with_a_gone_one_is_caught(
    tmp_path: Path, body: str, without: list[int], missing: list[str]
) -> None:
    (tmp_path / "tests" / "unit").mkdir(parents=True)
    (tmp_path / "tests" / "unit" / "x.py").write_text("def test_here() -> None:\n    pass\n")
    rows = catalogue_rows(f"## Lesson 1\n| Kind | Did | Sees | Test |\n{body}\n")
    assert rows_without_a_test(rows) == without
    assert missing_tests(rows, tmp_path) == missing
