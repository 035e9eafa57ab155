"""Every markdown document the code and docs cite by name (in capitals) is in the repository."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from course_lib.core.paths import REPO_ROOT

CITED = re.compile(r"\b([A-Z][A-Z_]+\.md)\b")
SUFFIXES = {".py", ".md", ".toml", ".cfg", ".txt", ".ipynb", ".yaml", ""}


def _tracked() -> list[Path]:
    try:
        out = subprocess.run(
            ["git", "ls-files"], cwd=REPO_ROOT, capture_output=True, text=True, check=True
        ).stdout
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("needs a git checkout")
    return [REPO_ROOT / line for line in out.splitlines()]


def test_cited_documents_exist() -> None:
    files = _tracked()
    names = {p.name for p in files}
    missing = []
    for path in files:
        if (
            path.suffix not in SUFFIXES
            or path.parts[-3:-1] == ("tests", "golden")
            or not path.is_file()
        ):
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        missing += [
            f"{path.relative_to(REPO_ROOT)} cites {m}"
            for m in CITED.findall(text)
            if m not in names
        ]
    assert not missing, missing
