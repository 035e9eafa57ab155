"""Files the lessons show and write: sources with line numbers, diffs, learner files."""

from __future__ import annotations

import difflib
import os
from pathlib import Path

from ..core.files.atomic_files import atomic_write
from ..core.paths import REPO_ROOT, learner_notebooks_dir

__all__ = [
    "LEARNER_DIR",
    "FileView",
    "atomic_write",
    "diff_text",
    "display_path",
    "numbered",
]

# Gitignored: what lessons write for the learner (edited params files, the panel's saves).
LEARNER_DIR = learner_notebooks_dir() / "my_files"


def display_path(path: str | os.PathLike[str]) -> str:
    """Return `path` as the learner would type it: relative to the repository when inside it."""
    resolved = Path(path).resolve()
    notebooks = learner_notebooks_dir().resolve()
    for base in (notebooks, REPO_ROOT):
        try:
            rel = resolved.relative_to(base)
        except ValueError:
            continue
        return str(rel) if base == notebooks else f"../{rel}"
    return str(path)


def numbered(text: str, first: int = 1, marks: set[int] | None = None) -> str:
    """Return `text` with line numbers (`>` marks the lines in `marks`)."""
    lines = text.splitlines()
    width = len(str(first + len(lines) - 1))
    marks = marks or set()
    out = [
        f"{'>' if n in marks else ' '} {n:>{width}} | {line}".rstrip()
        for n, line in enumerate(lines, start=first)
    ]
    return "\n".join(out) + "\n"


def diff_text(before: str, after: str, name: str) -> str:
    """Return a unified diff of two versions of a file (what `git diff` shows)."""
    lines = difflib.unified_diff(
        before.splitlines(keepends=True),
        after.splitlines(keepends=True),
        f"a/{name}",
        f"b/{name}",
    )
    return "".join(lines)


class FileView:
    """A file's text shown in a notebook: plain text for nbval, highlighted HTML for the eye."""

    def __init__(self, title: str, text: str, language: str = "") -> None:
        self.title = title
        self.body = text
        self.language = language

    def __repr__(self) -> str:
        return f"# {self.title}\n{self.body}"

    def _repr_html_(self) -> str:
        import html

        return (
            f'<div style="font-family:monospace;color:#555">{html.escape(self.title)}</div>'
            f'<pre style="margin:0;padding:6px;background:#f6f8fa">{html.escape(self.body)}</pre>'
        )


class Text:
    """Plain text shown as is in a notebook cell (no quotes, real line breaks)."""

    def __init__(self, text: str) -> None:
        self.text = text if text.endswith("\n") or not text else text + "\n"

    def __repr__(self) -> str:
        return self.text
