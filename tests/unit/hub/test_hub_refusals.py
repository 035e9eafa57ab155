"""`make hub` with bad input: one sentence naming the file and line or the missing piece, and
nothing started or written (no state folder, no account, no process)."""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from course_lib.core.errors import CourseError
from course_lib.core.paths import REPO_ROOT
from course_lib.hub.provision.environment import check_world_executable

needs_root = pytest.mark.skipif(os.geteuid() != 0, reason="the hub's checks run as root")


def _hub(
    tmp_path: Path, text: str, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    config = tmp_path / "hub.yaml"
    config.write_text(
        f"environment: {tmp_path / 'env'}\nstate: {tmp_path / 'state'}\n{text}", encoding="utf-8"
    )
    return subprocess.run(
        [sys.executable, "-m", "course_lib", "hub", "--config", str(config)],
        cwd=REPO_ROOT, capture_output=True, text=True, timeout=60, check=False,
        env={**os.environ, **(env or {})},
    )  # fmt: skip


def _nothing_started(tmp_path: Path) -> None:
    assert not (tmp_path / "state").exists(), "a refused hub left its state folder"
    assert not (tmp_path / "env").exists(), "a refused hub began building"


@needs_root
def test_a_taken_port_is_named_with_its_line(tmp_path: Path) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        result = _hub(tmp_path, f"learners: [zz-a]\nadmins: [zz-t]\nport: {port}\n")
    assert result.returncode == 1, result
    assert "hub.yaml, line 5: port:" in result.stderr and str(port) in result.stderr
    assert "Traceback" not in result.stderr
    _nothing_started(tmp_path)


@needs_root
def test_a_system_account_is_refused_with_its_line(tmp_path: Path) -> None:
    result = _hub(tmp_path, "learners:\n  - zz-a\n  - daemon\nadmins: [zz-t]\n")
    assert result.returncode == 1, result
    assert "hub.yaml, line 5: learners:" in result.stderr, result.stderr
    assert "'daemon' is an account of the system" in result.stderr
    _nothing_started(tmp_path)


@needs_root
def test_missing_npm_is_named_before_anything_starts(tmp_path: Path) -> None:
    empty = tmp_path / "bin"
    empty.mkdir()
    with socket.socket() as free:
        free.bind(("127.0.0.1", 0))
        port = free.getsockname()[1]
    result = _hub(
        tmp_path, f"learners: [zz-a]\nadmins: [zz-t]\nport: {port}\n", {"PATH": str(empty)}
    )
    assert result.returncode == 1, result
    assert result.stderr.startswith("npm is missing"), result.stderr
    assert "apt-get install nodejs npm" in result.stderr
    _nothing_started(tmp_path)


def test_a_private_interpreter_is_refused() -> None:
    folder = Path(tempfile.mkdtemp(prefix="course-hub-python-"))  # the temp folder, not pytest's
    try:
        python = folder / "python3"
        python.write_text("#!/bin/sh\n")
        python.chmod(0o755)
        folder.chmod(0o700)
        with pytest.raises(CourseError, match="closed to other users"):
            check_world_executable(python)
        folder.chmod(0o755)
        if (
            os.access(tempfile.gettempdir(), os.X_OK)
            and Path(tempfile.gettempdir()).stat().st_mode & 1
        ):
            check_world_executable(python)
    finally:
        shutil.rmtree(folder)
