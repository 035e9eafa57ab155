"""A lesson notebook as its book page (course_lib.book.lesson_pages), the book's staged
sources (build.stage_sources) and the key its recordings are kept under (recording)."""

from __future__ import annotations

import json
import shutil
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import nbformat
import pytest

from course_lib.book.build import BOOK_SOURCES, stage_sources
from course_lib.book.lesson_pages import lesson_page
from course_lib.book.recording import Recording, course_fingerprint
from course_lib.core.paths import NOTEBOOKS_DIR
from course_lib.lessons.catalogue import LESSONS

SPECS = {spec.number: spec for spec in LESSONS}
REPLAY_SRC = "../_static/replays/lesson07.html"
SPEED_SVG = '<svg xmlns="http://www.w3.org/2000/svg" width="8" height="4"><title>s</title></svg>'


class _Tags(HTMLParser):
    """Collect the start tags of an HTML fragment with their attributes."""

    def __init__(self) -> None:
        super().__init__()
        self.tags: list[tuple[str, dict[str, str | None]]] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append((tag, dict(attrs)))


def _tags(html: str, name: str) -> list[dict[str, str | None]]:
    parser = _Tags()
    parser.feed(html)
    return [attrs for tag, attrs in parser.tags if tag == name]


def _notebook(number: int) -> Any:
    return nbformat.read(NOTEBOOKS_DIR / SPECS[number].notebook, as_version=4)


def _html_outputs(nb: Any) -> list[str]:
    return [
        output["data"]["text/html"]
        for cell in nb.cells
        for output in cell.get("outputs", [])
        if "text/html" in output.get("data", {})
    ]


def _code_cell(nb: Any, call: str) -> Any:
    (cell,) = [c for c in nb.cells if c.cell_type == "code" and call in c.source]
    return cell


@pytest.fixture
def recording(tmp_path: Path) -> Recording:
    """A fake recording of lesson 7: a tiny replay page and speed plot picture."""
    replay = tmp_path / "lesson07.html"
    replay.write_text("<!doctype html><title>replay</title><p>replay</p>", encoding="utf-8")
    speed = tmp_path / "lesson07-speed.svg"
    speed.write_text(SPEED_SVG, encoding="utf-8")
    return Recording(7, replay, speed)


def test_a_lesson_page_says_how_to_run_it_right_after_its_title(recording: Recording) -> None:
    stored = _notebook(7)
    page = lesson_page(_notebook(7), SPECS[7], recording)
    assert len(page.cells) == len(stored.cells) + 1
    assert page.cells[0].source == stored.cells[0].source
    assert page.cells[0].source.startswith("# Lesson 7 ")
    added = page.cells[1]
    assert added.cell_type == "markdown"
    assert "Run this lesson" in added.source
    assert "notebooks/07_move_the_robot.ipynb" in added.source
    assert [c.source for c in page.cells[2:]] == [c.source for c in stored.cells[1:]]


def test_a_driving_lesson_shows_its_recorded_replay_in_place_of_the_live_view(
    recording: Recording,
) -> None:
    page = lesson_page(_notebook(7), SPECS[7], recording)
    (output,) = _code_cell(page, "lesson.world()").outputs
    (frame,) = _tags(output["data"]["text/html"], "iframe")
    assert frame["src"] == REPLAY_SRC
    assert frame["title"], "the replay's frame has no title for a screen reader"
    assert REPLAY_SRC in [a["href"] for a in _tags(output["data"]["text/html"], "a")]
    nbformat.validate(page)  # the page is still a notebook MyST-NB can read


def test_a_driving_lesson_shows_its_recorded_speed_plot_with_a_text(
    recording: Recording,
) -> None:
    page = lesson_page(_notebook(7), SPECS[7], recording)
    cell = _code_cell(page, "lesson.speed_plot()")
    (output,) = cell.outputs
    assert output["data"]["image/svg+xml"] == SPEED_SVG
    assert cell.metadata["mystnb"]["image"]["alt"].startswith("Lesson 7: the robot")


def test_no_output_of_a_lesson_page_links_a_learners_replay(recording: Recording) -> None:
    stored = _html_outputs(_notebook(7))
    assert any('href="my_files/replays/' in html for html in stored), "nothing to relink"
    page = _html_outputs(lesson_page(_notebook(7), SPECS[7], recording))
    assert not any("my_files/replays/" in html for html in page)  # neither link nor its text
    links = [a["href"] for html in page for a in _tags(html, "a")]
    assert links.count(REPLAY_SRC) == 2  # the replay's own link and the self-check's


def test_without_a_recording_the_self_check_says_no_replay_was_recorded(tmp_path: Path) -> None:
    page = lesson_page(_notebook(7), SPECS[7], None)
    html = _html_outputs(page)
    assert not any("<iframe" in text for text in html)
    assert not any('href="my_files/replays/' in text for text in html)
    assert not any("my_files/replays/" in text for text in html)
    assert any("No replay of this lesson was recorded for this book." in text for text in html)
    assert "The book runs nothing" in str(_code_cell(page, "lesson.world()").outputs)


def test_a_lesson_without_driving_keeps_its_stored_outputs_byte_for_byte() -> None:
    stored = _notebook(1)
    page = lesson_page(_notebook(1), SPECS[1], None)
    assert "Run this lesson" in page.cells[1].source
    del page.cells[1]
    assert [c.source for c in page.cells] == [c.source for c in stored.cells]

    def outputs(nb: Any) -> list[str]:
        return [json.dumps(c.get("outputs"), sort_keys=True) for c in nb.cells]

    assert outputs(page) == outputs(stored)
    assert not any("<iframe" in html for html in _html_outputs(page))


def test_the_staged_sources_hold_the_settings_the_guides_and_every_lesson(
    tmp_path: Path,
) -> None:
    src = tmp_path / "src"
    (src / "lessons").mkdir(parents=True)
    (src / "lessons" / "00_old.ipynb").write_text("{}")  # from an earlier build
    stage_sources(src, {})
    assert (src / "conf.py").is_file() and (src / "index.md").is_file()
    guides = sorted(p.name for p in (BOOK_SOURCES / "guides").glob("*.md"))
    assert guides and sorted(p.name for p in (src / "guides").glob("*.md")) == guides
    lessons = sorted(p.name for p in (src / "lessons").iterdir())
    assert lessons == sorted(spec.notebook for spec in LESSONS)
    for name in lessons:
        assert "Run this lesson" in nbformat.read(src / "lessons" / name, 4).cells[1].source
    assert list((src / "_static" / "replays").iterdir()) == []


def test_the_staged_sources_hold_each_recorded_replay(
    tmp_path: Path, recording: Recording
) -> None:
    src = tmp_path / "src"
    stage_sources(src, {7: recording})
    staged = src / "_static" / "replays" / "lesson07.html"
    assert staged.read_bytes() == recording.replay.read_bytes()
    assert REPLAY_SRC in str(nbformat.read(src / "lessons" / "07_move_the_robot.ipynb", 4))


COURSE_FILES = {
    "course_lib/x.py": "SPEED = 1\n",
    "course_lib/lessons/y.py": "STEP = 2\n",
    "config/a.yaml": "rate_hz: 30\n",
    "rosject/p/package.xml": "<package><name>p</name></package>\n",
    "rosject/p/p/node.py": "print('hi')\n",
    "environment.txt": "ros-jazzy-rclpy\n",
}


def _fake_repo(root: Path) -> Path:
    for name, text in COURSE_FILES.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


@pytest.mark.parametrize("name", sorted(COURSE_FILES))
def test_the_course_fingerprint_changes_with_each_course_file(tmp_path: Path, name: str) -> None:
    repo = _fake_repo(tmp_path)
    before = course_fingerprint(repo=repo)
    (repo / name).write_text(COURSE_FILES[name] + "# edited\n")
    assert course_fingerprint(repo=repo) != before


@pytest.mark.parametrize(
    "name",
    [
        "course_lib/__pycache__/x.py",
        "course_lib/lessons/__pycache__/y.cpython-311.pyc",
        "rosject/build/p/p/node.py",
        "rosject/install/p/share/p/package.xml",
        "rosject/log/latest_build/events.log",
        "rosject/p/__pycache__/node.cpython-311.pyc",
        "rosject/p/build/lib/p/node.py",
    ],
)
def test_the_course_fingerprint_ignores_build_outputs_and_caches(
    tmp_path: Path, name: str
) -> None:
    repo = _fake_repo(tmp_path)
    before = course_fingerprint(repo=repo)
    (repo / name).parent.mkdir(parents=True, exist_ok=True)
    (repo / name).write_text("generated\n")
    assert course_fingerprint(repo=repo) == before


def test_the_course_fingerprint_changes_when_a_file_is_added_or_renamed(
    tmp_path: Path,
) -> None:
    repo = _fake_repo(tmp_path)
    before = course_fingerprint(repo=repo)
    (repo / "config" / "b.yaml").write_text("")
    added = course_fingerprint(repo=repo)
    (repo / "config" / "b.yaml").rename(repo / "config" / "c.yaml")
    assert len({before, added, course_fingerprint(repo=repo)}) == 3


def test_the_course_fingerprint_does_not_depend_on_where_the_clone_is(tmp_path: Path) -> None:
    first = _fake_repo(tmp_path / "one")
    second = shutil.copytree(first, tmp_path / "elsewhere" / "two")
    assert course_fingerprint(repo=first) == course_fingerprint(repo=second)
