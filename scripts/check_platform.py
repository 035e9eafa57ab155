"""Stop early, in one sentence, on a machine the ROS 2 Jazzy wheels do not cover.

Also before anything is built: the course builds `tf2_msgs` (the message of /tf) from the
ROS 2 build wheels, which needs a C/C++ compiler, `make` and the Python headers.
"""

import platform
import shutil
import sys
import sysconfig
from pathlib import Path

# The ROS 2 Jazzy wheels also cover 3.10, but the pinned mujoco 4.0.0 and numpy 2.4.6 need 3.11+;
# `make test` runs on 3.11 and `make smoke-python` (scripts/smoke_python.sh) proves 3.12.
SUPPORTED = "Linux x86_64 with CPython 3.11 or 3.12"


def missing_build_tools() -> list[str]:
    """Return the Debian packages to install for the workspace build (empty: all there)."""
    need = []
    if not (shutil.which("c++") or shutil.which("g++")) or not shutil.which("cc"):
        need.append("g++")
    if not shutil.which("make"):
        need.append("make")
    if not (Path(sysconfig.get_paths()["include"]) / "Python.h").is_file():
        need.append("python{}.{}-dev".format(*sys.version_info[:2]))
    return need


def main() -> int:
    system, machine = platform.system(), platform.machine()
    version = sys.version_info[:2]
    problems = []
    if system != "Linux" or machine not in ("x86_64", "AMD64"):
        problems.append(f"this machine is {system} {machine}")
    if not (3, 11) <= version <= (3, 12) or platform.python_implementation() != "CPython":
        problems.append(
            f"{sys.executable} is {platform.python_implementation()} {version[0]}.{version[1]}"
        )
    if problems:
        print(
            f"The course runs on {SUPPORTED}, but {' and '.join(problems)}.\n"
            "Try: make lab PYTHON=python3.11 (any CPython 3.11 or 3.12 on Linux x86_64).",
            file=sys.stderr,
        )
        return 1
    need = missing_build_tools()
    if need:
        print(
            "The course builds the tf2_msgs messages with a C/C++ compiler, make and the Python "
            f"headers; install them first: sudo apt-get install {' '.join(need)}",
            file=sys.stderr,
        )
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
