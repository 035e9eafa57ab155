"""The README is a front door (under 120 lines, every lesson named) and the guides in
book/guides/ stand alone: one `# Title` each, no raw HTML, and no relative link of theirs or
of the README is broken (the file exists; a `#anchor` is one of its headings, as GitHub and
MyST make them). A guide links nothing outside `book/`: the built site holds only that."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from course_lib.core.paths import NOTEBOOKS_DIR, REPO_ROOT

README = REPO_ROOT / "README.md"
BOOK = REPO_ROOT / "book"
GUIDES = sorted((BOOK / "guides").glob("*.md"))
MAX_README_LINES = 120

FENCE = re.compile(r"^(```|~~~)[^\n]*\n.*?^\1[^\n]*$", re.MULTILINE | re.DOTALL)
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1", re.DOTALL)
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6}) +(.+?) *#* *$", re.MULTILINE)
RAW_HTML = re.compile(r"(?<!\\)<(?!https?://)[A-Za-z!/]")


def prose(text: str) -> str:
    """Return `text` without fenced blocks and code spans: what is left can link or hold HTML."""
    return CODE_SPAN.sub("", FENCE.sub("", text))


def slug(heading: str) -> str:
    """Return a heading's anchor as GitHub and MyST make it: Why `ros2`? -> why-ros2."""
    return re.sub(r"[^\w\- ]", "", heading.replace("`", "").strip().lower()).replace(" ", "-")


def anchors(page: Path) -> set[str]:
    """Return the anchors of every heading of `page`."""
    return {slug(m[2]) for m in HEADING.finditer(FENCE.sub("", page.read_text(encoding="utf-8")))}


def broken_links(page: Path, *, inside: Path | None = None) -> list[str]:
    """Return what is wrong with each relative link of `page`; `inside`: where targets must be."""
    problems = []
    for target in LINK.findall(prose(page.read_text(encoding="utf-8"))):
        if re.match(r"[a-z][a-z0-9+.-]*:", target):
            continue  # https://..., mailto:...
        name, _, anchor = target.partition("#")
        dest = (page.parent / name).resolve() if name else page.resolve()
        if inside is not None and not dest.is_relative_to(inside.resolve()):
            problems.append(f"{page.name}: {target} leaves {inside.name}/")
        elif not dest.is_file():
            problems.append(f"{page.name}: {target} names no file")
        elif anchor and anchor not in anchors(dest):
            problems.append(f"{page.name}: {target} names no heading of {dest.name}")
    return problems


def test_the_readme_is_a_front_door() -> None:
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) < MAX_README_LINES, f"README.md has {len(lines)} lines"
    text = "\n".join(lines)
    lessons = sorted(NOTEBOOKS_DIR.glob("[0-9][0-9]_*.ipynb"))
    missing = [nb.stem for nb in lessons if nb.stem not in text]
    assert not missing, f"README.md's lessons list lacks {missing}"
    linked = {Path(t.partition("#")[0]).name for t in LINK.findall(prose(text))}
    assert {g.name for g in GUIDES} <= linked, "README.md links every guide"


def test_no_relative_link_is_broken() -> None:
    problems = broken_links(README)
    for guide in GUIDES:
        problems += broken_links(guide, inside=BOOK)
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("guide", GUIDES, ids=lambda p: p.name)
def test_each_guide_has_one_title_and_no_raw_html(guide: Path) -> None:
    text = guide.read_text(encoding="utf-8")
    assert text.startswith("# "), "a guide starts with its `# Title` line"
    titles = [m[0] for m in HEADING.finditer(FENCE.sub("", text)) if m[1] == "#"]
    assert len(titles) == 1, titles
    assert not RAW_HTML.search(prose(text)), "GitHub hides `<name>`: write it as code or \\<name>"


# --- the checks fail on broken pages ------------------------------------------------------------
def test_a_broken_link_or_anchor_is_reported(tmp_path: Path) -> None:
    book = tmp_path / "book"
    (book / "guides").mkdir(parents=True)
    (tmp_path / "notes.md").write_text("# Notes\n")
    (book / "guides" / "other.md").write_text("# Other\n\n## Why `ros2`, here\n")
    page = book / "guides" / "page.md"
    page.write_text(
        "# Page\n\n[fine](other.md#why-ros2-here) [gone](missing.md) [bad](other.md#nowhere)\n"
        "[out](../../notes.md) ![pic](other.png) `[code](not-a-link.md)` [web](https://x.org)\n"
        "[self](#page)\n"
    )
    assert broken_links(page, inside=book) == [
        "page.md: missing.md names no file",
        "page.md: other.md#nowhere names no heading of other.md",
        "page.md: ../../notes.md leaves book/",
        "page.md: other.png names no file",
    ]


def test_raw_html_outside_code_is_found() -> None:
    assert RAW_HTML.search(prose("fails at once, Spawn failed: <name>'s server"))
    assert not RAW_HTML.search(prose("`/user/<name>/proxy/` and \\<name> and <https://x.org>"))
