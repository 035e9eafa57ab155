"""Capture what the real `ros2 pkg create` (ros2pkg 0.32.2) prints and writes, as golden data.

Run it with the real tool, outside the course (it is not installed here):

    python capture.py --ros2 <path of a real `ros2` with ros2pkg> > cases.json

Each case runs in an empty folder of its own with a fixed user (`learner`) and a HOME
without a git config, so the maintainer and the paths are the same on every machine; the
folder's absolute path is written as `<cwd>`.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

CASES: dict[str, list[str]] = {
    # "Using parameters in a class (Python)" and "Monitoring for parameter changes (Python)"
    "tutorial_python_parameters": [
        "--build-type", "ament_python", "--license", "Apache-2.0",
        "python_parameters", "--dependencies", "rclpy",
    ],
    # "Creating a package": the Python and C++ variants
    "tutorial_python_node": [
        "--build-type", "ament_python", "--license", "Apache-2.0",
        "--node-name", "my_node", "my_package",
    ],
    "tutorial_cmake_node": [
        "--build-type", "ament_cmake", "--license", "Apache-2.0",
        "--node-name", "my_node", "my_package",
    ],
    "python_every_flag": [
        "--build-type", "ament_python", "--license", "MIT",
        "--dependencies", "rclpy", "std_msgs",
        "--maintainer-name", "Ada Lovelace", "--maintainer-email", "ada@example.com",
        "--description", "Parameters, tried out", "--destination-directory", "src",
        "--node-name", "talker", "pkg_full",
    ],
    "python_library": [
        "--build-type", "ament_python", "--license", "BSD-3-Clause",
        "--node-name", "tool", "--library-name", "tool", "py_lib",
    ],
    "python_default_license": ["--build-type", "ament_python", "plain_pkg"],
    "python_format_2": [
        "--build-type", "ament_python", "--package-format", "2", "--license", "BSL-1.0", "fmt2",
    ],
    "python_named_test": ["--build-type", "ament_python", "test"],
    "cmake_default": ["--license", "Apache-2.0", "cpp_params", "--dependencies", "rclcpp"],
    "dependencies_take_the_name": ["--dependencies", "rclpy", "cpp_params"],
    "cmake_library": [
        "--build-type", "ament_cmake", "--license", "GPL-3.0-only",
        "--library-name", "my_lib", "cpp_lib",
    ],
    "plain_cmake": ["--build-type", "cmake", "--license", "MIT-0", "--node-name", "n", "cm"],
    "other_licenses": [
        "--build-type", "ament_python", "--license", "BSD-2-Clause", "lic_bsd2",
    ],
    "licenses_bsd2_0": ["--build-type", "ament_python", "--license", "BSD-2.0", "lic_bsd20"],
    "licenses_lgpl": ["--build-type", "ament_python", "--license", "LGPL-3.0-only", "lic_lgpl"],
    "license_list": ["--license", "?", "anything"],
    "no_name": [],
    "bad_build_type": ["--build-type", "catkin", "pkg"],
}  # fmt: skip


def _files(root: Path) -> dict[str, str]:
    return {
        str(p.relative_to(root)): p.read_text() for p in sorted(root.rglob("*")) if p.is_file()
    }


def _run(ros2: str, args: list[str], cwd: Path, env: dict[str, str]) -> dict[str, object]:
    done = subprocess.run(
        [ros2, "pkg", "create", *args], cwd=cwd, env=env, capture_output=True, text=True
    )
    return {
        "stdout": done.stdout.replace(str(cwd), "<cwd>"),
        "stderr": done.stderr.replace(str(cwd), "<cwd>"),
        "exit": done.returncode,
    }


def capture(ros2: str) -> list[dict[str, object]]:
    """Run every case and the already-exists case; return them as golden records."""
    records = []
    with tempfile.TemporaryDirectory() as home:
        env = {**os.environ, "HOME": home, "USER": "learner", "LOGNAME": "learner"}
        env.pop("GIT_CONFIG_GLOBAL", None)
        for case, args in [*CASES.items(), ("already_exists", CASES["tutorial_python_node"])]:
            with tempfile.TemporaryDirectory() as folder:
                cwd = Path(folder).resolve()
                if case == "already_exists":
                    (cwd / "my_package").mkdir()
                record = {"case": case, "args": args, **_run(ros2, args, cwd, env)}
                record["files"] = _files(cwd)
                record["dirs"] = sorted(
                    str(p.relative_to(cwd)) for p in cwd.rglob("*") if p.is_dir()
                )
                records.append(record)
    return records


def main() -> int:
    """Print the golden records as JSON."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ros2", required=True, help="the real ros2 executable")
    json.dump(capture(parser.parse_args().ros2), sys.stdout, indent=1, sort_keys=True)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
