"""The Makefile rebuilds the workspace for a changed build description, not for an edited file;
`make doctor` reports a stale set-up instead of rebuilding it."""

from __future__ import annotations

import os
import shutil
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.core.paths import REPO_ROOT, ROSJECT_DIR
from course_lib.tools.doctor import stale_steps

STAMP = "rosject/install/.built"
PACKAGE = ROSJECT_DIR / "parameter_tests"


def _up_to_date() -> bool:
    """Return True when `make` would not rebuild the workspace (make -q: question mode)."""
    result = subprocess.run(
        ["make", "-q", STAMP], cwd=REPO_ROOT, capture_output=True, check=False, timeout=60
    )
    return result.returncode == 0


@pytest.fixture
def built() -> None:
    if shutil.which("make") is None or not (REPO_ROOT / STAMP).exists():
        pytest.skip("needs make and a built workspace (`make setup`)")
    if not _up_to_date():
        pytest.skip("the workspace is already out of date here")


@pytest.fixture
def newer() -> Iterator:
    """Make a path newer than the stamp for one test; put its times back afterwards."""
    touched: list[tuple[Path, os.stat_result]] = []

    def touch(path: Path) -> None:
        touched.append((path, path.stat()))
        future = time.time() + 60
        os.utime(path, (future, future))

    yield touch
    for path, stat in touched:
        os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))


@pytest.mark.parametrize(
    "relpath",
    ["config/param_vel_node.yaml", "parameter_tests/parameter_tests_node.py", "launch"],
)
def test_edited_files_need_no_rebuild(built: None, newer, relpath: str) -> None:  # type: ignore[no-untyped-def]
    newer(
        PACKAGE / relpath / "test_parameters.launch.py"
        if relpath == "launch"
        else PACKAGE / relpath
    )
    assert _up_to_date()


@pytest.mark.parametrize("relpath", ["setup.py", "package.xml", "config"])
def test_build_description_or_file_list_rebuilds(built: None, newer, relpath: str) -> None:  # type: ignore[no-untyped-def]
    newer(PACKAGE / relpath)
    assert not _up_to_date()


def test_doctor_runs_no_build_step(built: None, newer) -> None:  # type: ignore[no-untyped-def]
    newer(PACKAGE / "setup.py")
    dry = subprocess.run(
        ["make", "-n", "doctor"], cwd=REPO_ROOT, capture_output=True, text=True, check=True
    )
    assert "course_lib build" not in dry.stdout and "pip install" not in dry.stdout, dry.stdout


def test_doctor_reports_the_stale_workspace(built: None, newer) -> None:  # type: ignore[no-untyped-def]
    newer(PACKAGE / "setup.py")
    stamp_time = (REPO_ROOT / STAMP).stat().st_mtime_ns
    lines = stale_steps()
    assert "ROS workspace (rosject/install): stale: `make setup` rebuilds it with colcon" in lines
    assert "environment (.venv): up to date" in lines
    assert (REPO_ROOT / STAMP).stat().st_mtime_ns == stamp_time


def test_doctor_says_up_to_date_when_it_is(built: None) -> None:
    assert all(line.endswith("up to date") for line in stale_steps())
