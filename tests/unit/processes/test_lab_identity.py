"""A lab's marker names a process by pid and start time: a later process that reuses the pid
(even another course process of the user) is never taken for the lab, so never signalled as
one."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.core.host.procfs import cmdline
from course_lib.core.paths import runtime_dir
from course_lib.core.waiting import wait_until
from course_lib.processes.ownership import is_course_lab


def lab_start_marker(pid: int) -> Path:
    """The marker a lab writes beside its others (processes.lab_markers.lab_start_marker)."""
    return runtime_dir() / f"lab-{pid}.start"


def start_time(pid: int) -> str:
    return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[19]


@pytest.fixture
def course_like() -> Iterator[int]:
    """A process of this user whose command names course_lib, as a lab's does."""
    process = subprocess.Popen(
        [sys.executable, "-c", "import time; time.sleep(60)", "course_lib", "lab"]
    )
    try:
        # until it has exec'd, the child shows its parent's command (ci: is_course_lab False)
        assert wait_until(lambda: "course_lib" in (cmdline(process.pid) or ()), 10.0)
        yield process.pid
    finally:
        process.kill()
        process.wait()
        lab_start_marker(process.pid).unlink(missing_ok=True)


def test_a_marker_whose_start_time_is_another_process_s_names_no_lab(course_like: int) -> None:
    lab_start_marker(course_like).write_text("12345")  # the lab that had this pid before
    assert not is_course_lab(course_like)


def test_a_marker_with_the_process_s_own_start_time_names_the_lab(course_like: int) -> None:
    lab_start_marker(course_like).write_text(start_time(course_like))
    assert is_course_lab(course_like)
