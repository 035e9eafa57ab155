"""The driving lessons' replays, recorded at build time from a real run of each lesson.

A lesson is run as a learner's first run would be: its notebook executed top to bottom in a
fresh kernel (its own ROS session, the real simulation and nodes) in a throwaway copy of the
notebooks, then one more cell keeps its replay and speed plot (`capture`). The recording is
kept under a key of everything that could change it (the notebook, the course's code, its
settings and ROS packages), so a rebuild of one commit reuses it and gives the same pages;
`--rerecord` runs the lessons again.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import tempfile
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

from ..core.paths import LEARNER_ROOT_ENV, NOTEBOOKS_DIR, REPO_ROOT
from ..lessons.catalogue import LESSONS
from ..lessons.catalogue.spec import LessonSpec
from .capture import replay_name, speed_name

__all__ = [
    "DRIVING",
    "Recording",
    "RecordingError",
    "course_fingerprint",
    "record_lesson",
    "recordings",
]

DRIVING = tuple(spec for spec in LESSONS if spec.driven_node)
# What a lesson's run depends on, besides its notebook (build outputs and caches excluded).
_INPUTS = (("course_lib", "*"), ("config", "*.yaml"), ("rosject", "*"))  # with the robot model
_INPUT_FILES = ("environment.txt",)
_SKIPPED_PARTS = {"__pycache__", "build", "install", "log"}
CELL_TIMEOUT_S = 180


class RecordingError(RuntimeError):
    """A lesson's real run failed: the book has no replay of it."""


@dataclass(frozen=True)
class Recording:
    """A lesson's recorded run: its replay page and its speed plot picture."""

    number: int
    replay: Path
    speed: Path


def _files(root: Path, pattern: str) -> Iterable[Path]:
    for path in sorted(root.rglob(pattern)):
        if path.is_file() and not _SKIPPED_PARTS & set(path.relative_to(root).parts):
            yield path


def course_fingerprint(repo: Path = REPO_ROOT) -> str:
    """Return a digest of the course's code, settings and ROS packages (what a run uses)."""
    digest = hashlib.sha256()
    for folder, pattern in _INPUTS:
        for path in _files(repo / folder, pattern):
            digest.update(path.relative_to(repo).as_posix().encode() + b"\0")
            digest.update(hashlib.sha256(path.read_bytes()).digest())
    for name in _INPUT_FILES:
        digest.update(name.encode() + b"\0" + hashlib.sha256((repo / name).read_bytes()).digest())
    return digest.hexdigest()


def _key(spec: LessonSpec, fingerprint: str) -> str:
    notebook = (NOTEBOOKS_DIR / spec.notebook).read_bytes()
    return hashlib.sha256(notebook + fingerprint.encode()).hexdigest()[:16]


def _recorded(folder: Path, number: int) -> Recording:
    return Recording(number, folder / replay_name(number), folder / speed_name(number))


def record_lesson(spec: LessonSpec, folder: Path, *, timeout: int = CELL_TIMEOUT_S) -> Recording:
    """Run lesson `spec` for real in a throwaway copy of the notebooks; keep its recording in
    `folder` (written whole or not at all)."""
    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError

    from ..lessons.texts import render_cells
    from ..tools.config_check import require_valid_config
    from ..tools.notebook_outputs import OUTPUT_ENV

    settings = require_valid_config(show_notes=False)["course.yaml"]
    with tempfile.TemporaryDirectory(prefix="course-book-") as tmp:
        (Path(tmp) / "notebooks" / "my_files").mkdir(parents=True)  # the learner's, empty
        nb = nbformat.read(NOTEBOOKS_DIR / spec.notebook, as_version=4)
        render_cells(spec.notebook, nb, settings)
        kept = Path(tmp) / "kept"
        nb.cells.append(
            nbformat.v4.new_code_cell(
                "from course_lib.book.capture import keep_for_book\n"
                f"keep_for_book(lesson, {str(kept)!r})"
            )
        )
        env = {**os.environ, **OUTPUT_ENV, LEARNER_ROOT_ENV: tmp}
        client = NotebookClient(
            nb,
            timeout=timeout,
            kernel_name="python3",
            resources={"metadata": {"path": str(NOTEBOOKS_DIR)}},
            record_timing=False,
        )
        try:  # in the course's notebooks folder, as nbval runs it (its `../rosject/` paths)
            client.execute(env=env, cwd=str(NOTEBOOKS_DIR), stderr=subprocess.DEVNULL)
        except CellExecutionError as error:
            raise RecordingError(
                f"lesson {spec.number} ({spec.notebook}) failed in a real run: "
                f"{error.ename}: {error.evalue}"
            ) from None
        staged = folder.with_name(folder.name + ".partial")
        shutil.rmtree(staged, ignore_errors=True)
        shutil.copytree(kept, staged)
        shutil.rmtree(folder, ignore_errors=True)
        staged.rename(folder)
    return _recorded(folder, spec.number)


def recordings(
    cache: Path,
    *,
    rerecord: bool = False,
    lessons: Iterable[LessonSpec] = DRIVING,
    say: Callable[[str], None] = print,
) -> dict[int, Recording]:
    """Return each driving lesson's recording: the one kept in `cache` for the lesson's
    current inputs, or a new run of the lesson (older recordings of it are removed)."""
    fingerprint = course_fingerprint()
    found: dict[int, Recording] = {}
    for spec in lessons:
        folder = cache / f"lesson{spec.number:02d}-{_key(spec, fingerprint)}"
        recording = _recorded(folder, spec.number)
        if rerecord or not (recording.replay.is_file() and recording.speed.is_file()):
            started = time.monotonic()
            recording = record_lesson(spec, folder)
            say(f"recorded lesson {spec.number}'s run: {time.monotonic() - started:.1f} s")
        for old in cache.glob(f"lesson{spec.number:02d}-*"):
            if old != folder:
                shutil.rmtree(old, ignore_errors=True)
        found[spec.number] = recording
    return found
