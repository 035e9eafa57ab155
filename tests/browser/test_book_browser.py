"""The book (`make book`, issue 64), built once from this clone: no warning, no broken link,
the same pages from a second build of one commit, and in Chromium every page loads with no
console error, its replays play, axe finds nothing serious in the course's content, and the
site works opened from a folder or served under any path.

The driving lessons run for real once (their replays and speed plots); the second build
reuses those recordings, as a rebuild of one commit does.
"""

from __future__ import annotations

import filecmp
import functools
import http.server
import shutil
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pytest
from accessibility import audit, report

from course_lib.book.build import BookBuild, build_book
from course_lib.book.lesson_pages import REPLAYS_DIR
from course_lib.lessons.catalogue import LESSONS

pytestmark = [pytest.mark.browser, pytest.mark.sim]

ANIMATION_TIME = "viewer.animator.actions.reduce((m, a) => Math.max(m, a.time), 0)"
CONTENT = "article"  # the page's own text, code and outputs (the theme's frame around it is not)
GUIDES = sorted(
    p.stem for p in (Path(__file__).resolve().parents[2] / "book" / "guides").glob("*.md")
)


@pytest.fixture(scope="module")
def book(tmp_path_factory: pytest.TempPathFactory) -> BookBuild:
    """The book built from this clone (the driving lessons run for real)."""
    return build_book(tmp_path_factory.mktemp("book"))


def _pages(site: Path) -> list[Path]:
    lessons = [site / "lessons" / spec.notebook.replace(".ipynb", ".html") for spec in LESSONS]
    guides = [site / "guides" / f"{name}.html" for name in GUIDES]
    return [site / "index.html", *lessons, *guides]


def test_the_book_builds_with_no_warning_and_every_link_resolving(book: BookBuild) -> None:
    assert book.warnings == "", book.warnings
    assert book.broken == [], "\n".join(map(str, book.broken))
    for page in _pages(book.site):
        assert page.is_file(), f"{page.relative_to(book.site)} is missing from the book"
    replays = sorted(p.name for p in (book.site / REPLAYS_DIR).glob("*.html"))
    driving = sorted(f"lesson{s.number:02d}.html" for s in LESSONS if s.driven_node)
    assert replays == driving


def _differences(left: Path, right: Path) -> list[str]:
    """Return the files that differ between two folders, or are in one only."""
    found: list[str] = []
    compared = filecmp.dircmp(left, right)
    found += [f"only in the first: {n}" for n in compared.left_only]
    found += [f"only in the second: {n}" for n in compared.right_only]
    _, mismatch, errors = filecmp.cmpfiles(left, right, compared.common_files, shallow=False)
    found += [f"differs: {n}" for n in mismatch + errors]
    for sub in compared.common_dirs:
        found += [f"{sub}/{d}" for d in _differences(left / sub, right / sub)]
    return found


def test_two_builds_of_one_commit_give_the_same_pages(book: BookBuild, tmp_path: Path) -> None:
    again = build_book(tmp_path / "again", recorded_in=book.site.parent / "recordings")
    assert again.ok, again.warnings
    assert _differences(book.site, again.site) == []


def _open(browser: Any, url: str, width: int = 1280) -> tuple[Any, Any, list[str]]:
    context = browser.new_context(viewport={"width": width, "height": 900})
    page = context.new_page()
    errors: list[str] = []

    def console(message: Any) -> None:
        # a resource that did not load is said below with its address
        if message.type == "error" and not message.text.startswith("Failed to load resource"):
            errors.append(message.text)

    def response(answer: Any) -> None:
        # the browser's own request for the server's /favicon.ico is outside the site
        if answer.status >= 400 and urlsplit(answer.url).path != "/favicon.ico":
            errors.append(f"{answer.status} for {answer.url}")

    page.on("console", console)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("requestfailed", lambda r: errors.append(f"failed to load {r.url}"))
    page.on("response", response)
    page.goto(url, wait_until="load")
    return context, page, errors


def _replay_plays(page: Any) -> None:
    """Bring the page's replay into view and check its animation's time moves on."""
    frame_element = page.locator("iframe.course-replay")
    frame_element.scroll_into_view_if_needed()
    frame = frame_element.element_handle().content_frame()
    frame.wait_for_function("() => typeof viewer === 'object' && viewer.animator", timeout=30_000)
    first = frame.evaluate(ANIMATION_TIME)
    frame.wait_for_function(f"{ANIMATION_TIME} > {first} + 0.2", timeout=30_000)


def test_every_page_loads_with_no_console_error_plays_its_replay_and_passes_axe(
    browser: Any, book: BookBuild, served: str, artifacts: Path, axe_js: str
) -> None:
    """Each page loaded once (served: axe reads the stylesheets, which a page opened from a
    folder may not fetch): its pictures drawn, its replay playing, no console error, and axe
    finding nothing serious in its own content (a replay's frame, audited in
    test_accessibility_pages, is not part of it)."""
    found: list[str] = []
    for path in _pages(book.site):
        context, page, errors = _open(browser, served + path.relative_to(book.site).as_posix())
        try:
            name = path.relative_to(book.site).as_posix()
            for picture in page.locator("article img").all():  # drawn, not a broken image
                picture.scroll_into_view_if_needed()
                drawn = picture.evaluate("(i) => i.complete && i.naturalWidth > 0")
                assert drawn, f"{name}: {picture.get_attribute('alt')} is not drawn"
            if page.locator("iframe.course-replay").count():
                _replay_plays(page)
                page.screenshot(path=str(artifacts / f"{path.stem}.png"))
            violations = audit(page, axe_js, [CONTENT])
            if violations:
                found.append(f"{name}: {report(violations)}")
            page.wait_for_timeout(200)
            assert errors == [], f"{name}: {errors}"
        finally:
            context.close()
    assert found == [], "\n".join(found)


def test_the_driving_lessons_show_their_replay_and_speed_plot(book: BookBuild) -> None:
    for spec in LESSONS:
        html = (book.site / "lessons" / spec.notebook.replace(".ipynb", ".html")).read_text()
        replay = f"../{REPLAYS_DIR}/lesson{spec.number:02d}.html"
        assert "Run this lesson" in html, spec.notebook
        assert (replay in html) == bool(spec.driven_node), spec.notebook
        assert "my_files/replays/" not in html, f"{spec.notebook} links a learner's replay"
        assert "run this cell to see it" not in html, f"{spec.notebook}: a lab's placeholder"
    lesson7 = (book.site / "lessons" / "07_move_the_robot.html").read_text()
    assert 'alt="Lesson 7: the robot' in lesson7, "the speed plot picture has no text"


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args: Any) -> None:
        """Say nothing per request (the test's own output stays readable)."""


@pytest.fixture(scope="module")
def served(book: BookBuild, tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """Serve the site under a sub-path (`/courses/ros2/book/`) over HTTP; yield its URL."""
    root = tmp_path_factory.mktemp("www")
    shutil.copytree(book.site, root / "courses" / "ros2" / "book")
    handler = functools.partial(_QuietHandler, directory=str(root))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/courses/ros2/book/"
    finally:
        server.shutdown()
        server.server_close()


def test_a_lesson_opened_from_the_folder_plays_its_replay(browser: Any, book: BookBuild) -> None:
    path = book.site / "lessons" / "07_move_the_robot.html"
    context, page, errors = _open(browser, path.as_uri())
    try:
        _replay_plays(page)
        page.wait_for_timeout(200)
        assert errors == [], errors
    finally:
        context.close()


def test_the_site_works_served_under_a_sub_path_and_on_a_phone(browser: Any, served: str) -> None:
    context, page, errors = _open(browser, served, width=390)
    try:
        lesson7 = "Lesson 7 · Move the robot with a parameter"
        page.locator(CONTENT).get_by_role("link", name=lesson7).click()
        page.wait_for_load_state("load")
        assert page.url == served + "lessons/07_move_the_robot.html"
        _replay_plays(page)
        wide = page.evaluate("document.documentElement.scrollWidth")
        assert wide <= 390 + 1, f"the lesson page scrolls sideways on a phone ({wide} px)"
        assert errors == [], errors
    finally:
        context.close()
