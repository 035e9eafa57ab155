"""The Makefile rebuilds the workspace for a changed build description, not for an edited file."""

from __future__ import annotations

import os
import shutil
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.paths import REPO_ROOT, ROSJECT_DIR

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
