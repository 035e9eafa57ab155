"""Getting started's "What survives what": every fault it promises names a test that exists."""

from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
GUIDE = REPO / "book" / "guides" / "getting-started.md"
SECTION = "## What survives what"


def missing_tests(text: str, repo: Path = REPO) -> list[str]:
    """Return the rows of the section in `text` whose last column names no existing test."""
    body = text.split(SECTION, 1)[1].split("\n## ", 1)[0]
    rows = [line for line in body.splitlines() if line.startswith("| ") and "---" not in line]
    problems = []
    for row in rows[1:]:  # the first is the header
        named = re.findall(r"`(tests/[^`]+\.py)`", row.rstrip(" |").rsplit(" | ", 1)[-1])
        if not named or any(not (repo / path).is_file() for path in named):
            problems.append(row[:100])
    return problems


def test_every_fault_in_the_table_names_a_test_that_exists() -> None:
    text = GUIDE.read_text(encoding="utf-8")
    assert SECTION in text
    assert missing_tests(text) == []


def test_a_row_without_its_test_is_reported() -> None:
    text = (
        f"{SECTION}\n\n| Fault | Seen | Kept | Test |\n| --- | --- | --- | --- |\n"
        "| a fault | x | y | `tests/nowhere/test_gone.py` |\n| another | x | y | none |\n"
    )
    assert len(missing_tests(text)) == 2
