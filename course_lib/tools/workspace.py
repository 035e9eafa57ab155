"""Build the ROS workspace in rosject/ with colcon, as a learner would on a ROS 2 machine.

Besides the Python packages, rosject/ holds `tf2_msgs` (the message of /tf), an interface
package that has no wheel: colcon builds it with CMake from the ROS 2 build wheels installed in
this virtualenv, which therefore serves as the underlay prefix (AMENT_PREFIX_PATH and
CMAKE_PREFIX_PATH), like /opt/ros/jazzy on a ROS machine.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import sysconfig
from collections.abc import Mapping
from pathlib import Path

from ..core.paths import PACKAGE_DIR, REPO_ROOT, ROSJECT_DIR, prepend, venv_bin_dir

__all__ = ["BUILD_STAMP", "build_env", "build_workspace", "cmake_args", "make_flags"]

BUILD_STAMP = ROSJECT_DIR / "install" / ".built"
CHECK_PLATFORM = REPO_ROOT / "scripts" / "check_platform.py"  # also names a missing compiler
WHEEL_FIXUPS = PACKAGE_DIR / "cmake" / "wheel_fixups.cmake"
# What in MAKEFLAGS already says how many jobs make runs (colcon then adds nothing of its own)
_JOBS_FLAG = re.compile(r"(?:^|\s)-[jl]|--jobs|--load-average|--jobserver")


def build_env(base: Mapping[str, str] | None = None) -> dict[str, str]:
    """Return `base` with this virtualenv as the underlay colcon and CMake build against."""
    env = dict(os.environ if base is None else base)
    prefix = str(Path(sys.prefix))
    for variable in ("AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH"):
        env[variable] = prepend(prefix, env.get(variable))
    env["PATH"] = prepend(str(venv_bin_dir()), env.get("PATH"))  # the pinned cmake
    env["MAKEFLAGS"] = make_flags(env.get("MAKEFLAGS", ""))
    return env


def make_flags(inherited: str) -> str:
    """Return MAKEFLAGS for the workspace's builds: `inherited` with one job per core added
    unless it sets the jobs already (pure).

    colcon adds `-j<cores> -l<cores>` when MAKEFLAGS sets no jobs, and the load limit compiles
    one file at a time on a busy machine (the class hub's environment, built while the tests
    run). `make setup` always hands its recipes a MAKEFLAGS, empty or " --no-print-directory",
    so the variable is extended, not only set where missing.
    """
    if _JOBS_FLAG.search(inherited):
        return inherited
    return f"{inherited} -j{os.cpu_count() or 1}".strip()


def python_include_dirs() -> list[str]:
    """Return this interpreter's Python and numpy include folders (for the wheel fix-up)."""
    import numpy

    return [sysconfig.get_paths()["include"], numpy.get_include()]


def cmake_args() -> list[str]:
    """Return the CMake options of every CMake package in the workspace."""
    return [
        "-DBUILD_TESTING=OFF",
        f"-DPython3_EXECUTABLE={sys.executable}",
        f"-DCMAKE_PROJECT_INCLUDE={WHEEL_FIXUPS}",
        f"-DCOURSE_PYTHON_INCLUDE_DIRS={';'.join(python_include_dirs())}",
        # The built libraries find each other (and the Python extensions find them) without
        # LD_LIBRARY_PATH, so any process of the course can import the built messages.
        "-DCMAKE_INSTALL_RPATH=$ORIGIN;$ORIGIN/../../..",
    ]


def build_workspace(*, quiet: bool = True, workspace: Path = ROSJECT_DIR) -> int:
    """Run `colcon build` in `workspace` (rosject/); return its exit code."""
    checked = subprocess.run([sys.executable, str(CHECK_PLATFORM)], check=False)
    if checked.returncode != 0:  # it said, in one sentence, what to install
        return checked.returncode
    argv = [
        str(venv_bin_dir() / "colcon"),
        "build",
        "--merge-install",
        "--symlink-install",
        "--event-handlers",
        "console_start_end+" if quiet else "console_direct+",
        "--cmake-args",
        *cmake_args(),
    ]
    print(f"Building the ROS workspace: cd {workspace.name} && colcon {' '.join(argv[1:7])}")
    sys.stdout.flush()
    done = subprocess.run(argv, cwd=workspace, env=build_env(), check=False)
    if done.returncode == 0:
        (workspace / "install" / ".built").touch()
    else:
        print(
            f"colcon build failed; the log is in {workspace.name}/log/latest_build/.\n"
            "Try: make clean && make setup",
            file=sys.stderr,
        )
    return done.returncode
