"""Build the ROS workspace in rosject/ with colcon, as a learner would on a ROS 2 machine."""

from __future__ import annotations

import subprocess
import sys

from .paths import ROSJECT_DIR, WORKSPACE_INSTALL_DIR, venv_bin_dir

__all__ = ["BUILD_STAMP", "build_workspace"]

BUILD_STAMP = WORKSPACE_INSTALL_DIR / ".built"


def build_workspace(*, quiet: bool = True) -> int:
    """Run `colcon build --merge-install --symlink-install` in rosject/; return its exit code."""
    argv = [
        str(venv_bin_dir() / "colcon"),
        "build",
        "--merge-install",
        "--symlink-install",
        "--event-handlers",
        "console_start_end+" if quiet else "console_direct+",
    ]
    print(f"Building the ROS workspace: cd rosject && {' '.join(argv[1:])}", flush=True)
    done = subprocess.run(argv, cwd=ROSJECT_DIR, check=False)
    if done.returncode == 0:
        BUILD_STAMP.touch()
    else:
        print(
            "colcon build failed; the log is in rosject/log/latest_build/.\n"
            "Try: make clean && make setup",
            file=sys.stderr,
        )
    return done.returncode
