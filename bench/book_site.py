"""The book (`make book`): build time with the driving lessons' recordings reused and while
recording them, and the site's size (its largest page and replay).

`python -m bench.book_site [--out DIR] [--rerecord]`: without `--out` the build goes to a
throwaway folder, so the lessons are recorded (each runs for real); with it, recordings kept
in DIR are reused unless `--rerecord`.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

from course_lib.book.build import BookBuild, build_book
from course_lib.book.lesson_pages import REPLAYS_DIR
from course_lib.book.recording import RecordingError, recordings

MIB = 1024 * 1024


def _record(cache: Path, *, rerecord: bool) -> tuple[float, list[str]]:
    """Return the seconds to get every driving lesson's recording, and what was recorded."""
    said: list[str] = []
    started = time.monotonic()
    recordings(cache, rerecord=rerecord, say=said.append)
    return time.monotonic() - started, said


def _largest(files: list[Path]) -> tuple[Path, int]:
    path = max(files, key=lambda p: p.stat().st_size)
    return path, path.stat().st_size


def _report_site(site: Path) -> None:
    files = [p for p in site.rglob("*") if p.is_file()]
    total = sum(p.stat().st_size for p in files)
    replays = sorted((site / REPLAYS_DIR).glob("*.html"))
    pages = [p for p in site.rglob("*.html") if p not in replays]
    print(f"site: {total / MIB:.1f} MiB in {len(files)} files ({len(pages)} pages)")
    page, size = _largest(pages)
    print(f"largest page: {page.relative_to(site)}, {size / 1024:.0f} KiB")
    if replays:
        replay, size = _largest(replays)
        print(f"largest replay: {replay.relative_to(site)}, {size / MIB:.2f} MiB")


def _problems(build: BookBuild) -> bool:
    if build.warnings:
        print(build.warnings, file=sys.stderr)
    for link in build.broken:
        print(f"broken link: {link}", file=sys.stderr)
    return not build.ok


def run(out: Path, *, rerecord: bool) -> int:
    """Build the book into `out` and print its figures; return 1 if the build had problems."""
    cache = out / "recordings"
    try:
        record_s, said = _record(cache, rerecord=rerecord)
    except RecordingError as error:
        sys.exit(f"no book: {error}")
    build = build_book(out, recorded_in=cache)
    for line in said:
        print(line)
    if said:
        print(f"recording {len(said)} lessons: {record_s:.1f} s")
    else:
        print(f"recordings: all reused ({record_s:.1f} s to check them)")
    print(
        f"build, recordings reused: {build.seconds:.1f} s; "
        f"with recording: {record_s + build.seconds:.1f} s"
    )
    _report_site(build.site)
    return 1 if _problems(build) else 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.book_site", description=__doc__)
    parser.add_argument("--out", type=Path, help="the build folder (default: a throwaway one)")
    parser.add_argument("--rerecord", action="store_true", help="run the lessons again")
    options = parser.parse_args(argv)
    if options.out is not None:
        return run(options.out.resolve(), rerecord=options.rerecord)
    with tempfile.TemporaryDirectory(prefix="bench-book-") as out:
        return run(Path(out), rerecord=options.rerecord)


if __name__ == "__main__":
    sys.exit(main())
