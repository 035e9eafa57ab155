"""Stop early, in one sentence, on a machine the ROS 2 Jazzy wheels do not cover."""

import platform
import sys

# The ROS 2 Jazzy wheels also cover 3.10, but the pinned mujoco 4.0.0 and numpy 2.4.6 need 3.11+;
# `make test` runs on 3.11 and `make smoke-python` (scripts/smoke_python.sh) proves 3.12.
SUPPORTED = "Linux x86_64 with CPython 3.11 or 3.12"


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
    return 0


if __name__ == "__main__":
    sys.exit(main())
