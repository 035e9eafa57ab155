"""`make doctor` proves the install works (rclpy, tf2_msgs, the simulation's offscreen camera):
it exits 0 on this install and non-zero on a broken one, naming what is broken."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from suite_env import independent_env

from course_lib.core.paths import REPO_ROOT

pytestmark = [pytest.mark.ros, pytest.mark.sim]

# a fresh shell's: nothing sourced, and the ROS wheels' start-up (which sets the library path
# once, and marks that it did) left to run again in the doctor's own process
_SOURCED = (
    "AMENT_PREFIX_PATH",
    "COLCON_PREFIX_PATH",
    "PYTHONPATH",
    "LD_LIBRARY_PATH",
    "_ROS_WHEELS_BOOTSTRAP_COMPLETE",
)


def _doctor(cwd: Path, **extra: str) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in independent_env(**extra).items() if k not in _SOURCED}
    return subprocess.run(
        [sys.executable, "-m", "course_lib", "doctor"], cwd=cwd, env=env,
        capture_output=True, text=True, timeout=240, check=False,
    )  # fmt: skip


def test_this_install_passes_every_check() -> None:
    done = _doctor(REPO_ROOT)
    said = done.stdout + done.stderr
    assert done.returncode == 0, said
    for name in ("rclpy", "tf2_msgs", "rendering"):
        assert f"ok: {name}: " in done.stdout, said
    assert "rendered with MUJOCO_GL=egl" in done.stdout


def test_a_copy_whose_workspace_was_never_built_fails(tmp_path: Path) -> None:
    """The course without rosject/install (`make setup` not run to its end): no tf2_msgs."""
    for part in ("course_lib", "config"):
        shutil.copytree(
            REPO_ROOT / part, tmp_path / part, ignore=shutil.ignore_patterns("__pycache__")
        )
    done = _doctor(tmp_path)
    said = done.stdout + done.stderr
    assert done.returncode != 0, said
    assert "FAILED: tf2_msgs: " in done.stdout and "ok: rclpy: " in done.stdout, said
    assert "The install is broken (tf2_msgs)" in done.stderr, said


def test_a_middleware_not_installed_and_no_renderer_fail_their_checks() -> None:
    done = _doctor(REPO_ROOT, RMW_IMPLEMENTATION="rmw_no_such_cpp", MUJOCO_GL="no-such-gl")
    said = done.stdout + done.stderr
    assert done.returncode != 0, said
    assert "FAILED: rclpy: " in done.stdout and "FAILED: rendering: " in done.stdout, said
    # tf2_msgs's check loads rcl too, so it may fail as well: the line names both at least
    broken = re.search(r"The install is broken \(([^)]*)\)", done.stderr)
    assert broken and {"rclpy", "rendering"} <= set(broken[1].split(", ")), said
