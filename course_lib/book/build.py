"""Build the book: stage its sources, run Sphinx (warnings are errors), check its links.

Sources: `book/` (the front page, the guides, Sphinx's settings) and the lessons' notebooks
made into pages (`lesson_pages`), staged in `<out>/src`; the site lands in `<out>/html`, with
relative links only, so it works opened from a folder or served under any path.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from ..core.paths import NOTEBOOKS_DIR, REPO_ROOT
from ..lessons.catalogue import LESSONS
from .lesson_pages import REPLAYS_DIR, lesson_page
from .links import BrokenLink, broken_links
from .recording import Recording, recordings

__all__ = ["BOOK_SOURCES", "DEFAULT_OUT", "BookBuild", "build_book", "run_sphinx", "stage_sources"]

BOOK_SOURCES = REPO_ROOT / "book"
DEFAULT_OUT = REPO_ROOT / "build" / "book"


@dataclass(frozen=True)
class BookBuild:
    """What a build made: the site's folder, Sphinx's warnings, the links that do not resolve."""

    site: Path
    warnings: str
    broken: list[BrokenLink]
    seconds: float

    @property
    def ok(self) -> bool:
        return not self.warnings and not self.broken


def stage_sources(src: Path, recorded: dict[int, Recording]) -> None:
    """Write the book's Sphinx sources into `src` (emptied first)."""
    import nbformat

    shutil.rmtree(src, ignore_errors=True)
    shutil.copytree(BOOK_SOURCES, src, ignore=shutil.ignore_patterns("__pycache__"))
    (src / "lessons").mkdir()
    for spec in LESSONS:
        nb = nbformat.read(NOTEBOOKS_DIR / spec.notebook, as_version=4)
        page = lesson_page(nb, spec, recorded.get(spec.number))
        nbformat.write(page, src / "lessons" / spec.notebook)
    replays = src / REPLAYS_DIR
    replays.mkdir(parents=True, exist_ok=True)
    for recording in recorded.values():
        shutil.copyfile(recording.replay, replays / recording.replay.name)


def run_sphinx(src: Path, site: Path, doctrees: Path) -> str:
    """Run Sphinx's HTML builder in a process of its own; return its warnings (empty: none).

    Its own process: an extension's set-up outlives its build in the process that ran it
    (after a build with myst_nb, another process-mate's `.md` page still asked for myst_nb's
    parser: "Source parser for myst-nb not registered")."""
    argv = [
        sys.executable,
        # the extensions' use of APIs Sphinx will remove is theirs to fix, not a page's fault
        # (under a "warnings are errors" filter, such as the tests', it would stop the build)
        "-W", "ignore::DeprecationWarning",
        "-W", "ignore::PendingDeprecationWarning",
        "-m", "sphinx",
        "-b", "html", "-q", "-E", "-d", str(doctrees), str(src), str(site),
    ]  # fmt: skip
    done = subprocess.run(argv, capture_output=True, text=True, check=False)
    text = done.stderr.strip()
    if done.returncode and not text:
        text = f"sphinx-build exited with status {done.returncode}"
    return text


def build_book(
    out: Path = DEFAULT_OUT,
    *,
    record: bool = True,
    rerecord: bool = False,
    recorded_in: Path | None = None,
) -> BookBuild:
    """Build the book into `out/html`. The driving lessons' runs are kept in `recorded_in`
    (default `out/recordings`) and recorded there when missing or `rerecord`; with `record`
    false their pages keep the notebooks' stored placeholders."""
    started = time.monotonic()
    cache = recorded_in or out / "recordings"
    recorded = recordings(cache, rerecord=rerecord) if record else {}
    site = out / "html"
    shutil.rmtree(site, ignore_errors=True)
    shutil.rmtree(out / "doctrees", ignore_errors=True)
    stage_sources(out / "src", recorded)
    warnings = run_sphinx(out / "src", site, out / "doctrees")
    broken = broken_links(site) if site.is_dir() else []
    return BookBuild(site, warnings, broken, time.monotonic() - started)


def main(argv: list[str] | None = None) -> int:
    """`make book`: build, print what is wrong, exit non-zero if anything is."""
    import argparse

    parser = argparse.ArgumentParser(
        prog="python -m course_lib.book",
        description="Build the course as a static site (build/book/html/index.html).",
    )
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT, help="the build folder")
    parser.add_argument(
        "--rerecord", action="store_true", help="run the driving lessons again for their replays"
    )
    options = parser.parse_args(argv)
    build = build_book(options.out.resolve(), rerecord=options.rerecord)
    if build.warnings:
        print(build.warnings, file=sys.stderr)
    for link in build.broken:
        print(f"broken link: {link}", file=sys.stderr)
    where = build.site / "index.html"
    verdict = "built" if build.ok else "built with problems (above)"
    print(f"The book is {verdict} in {build.seconds:.1f} s: open {where}")
    return 0 if build.ok else 1
