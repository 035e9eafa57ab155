"""A lab's marker names a process by pid and start time: a later process that reuses the pid
(even another course process of the user) is never taken for the lab, so never signalled as
one; the spawn tag tells a process the course started from one that inherited its tags."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator

import pytest

from course_lib.lab_markers import lab_start_marker
from course_lib.ownership import is_course_lab
from course_lib.processes import command_tag, runs_as_spawned, start_time


@pytest.fixture
def course_like() -> Iterator[int]:
    """A process of this user whose command names course_lib, as a lab's does."""
    process = subprocess.Popen(
        [sys.executable, "-c", "import time; time.sleep(60)", "course_lib", "lab"]
    )
    try:
        yield process.pid
    finally:
        process.kill()
        process.wait()
        lab_start_marker(process.pid).unlink(missing_ok=True)


def test_a_marker_whose_start_time_is_another_process_s_names_no_lab(course_like: int) -> None:
    lab_start_marker(course_like).write_text("12345")  # the lab that had this pid before
    assert not is_course_lab(course_like)


def test_a_marker_with_the_process_s_own_start_time_names_the_lab(course_like: int) -> None:
    lab_start_marker(course_like).write_text(start_time(course_like) or "")
    assert is_course_lab(course_like)


def test_the_spawn_tag_matches_the_command_as_proc_shows_it() -> None:
    tag = command_tag(["jupyter", "lab", "--no-browser"])
    # run through a `#!` interpreter, from PATH: the interpreter comes first, the path in full
    assert runs_as_spawned(["/venv/bin/python3", "/venv/bin/jupyter", "lab", "--no-browser"], tag)
    assert not runs_as_spawned(["/bin/bash", "--rcfile", "lab_bashrc.bash", "-i"], tag)
    assert not runs_as_spawned(["sleep", "600"], tag)
    assert not runs_as_spawned(["/venv/bin/jupyter", "lab"], tag)
