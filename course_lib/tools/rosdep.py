"""The course's `rosdep`: are the dependencies in each package.xml installed? (no root, no apt)

In the course, ROS 2 and its Python libraries come from the course's environment
(environment.txt), not from apt: `rosdep install` checks every package.xml under the given
paths against what is installed and says so in one line, or names what is missing.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import xml.etree.ElementTree as ET
from collections.abc import Iterator, Sequence
from pathlib import Path

__all__ = ["main", "missing_keys", "package_manifests"]

_RUN_TAGS = ("depend", "build_depend", "buildtool_depend", "exec_depend", "build_export_depend")
_TEST_TAGS = ("test_depend",)
_PYTHON_MODULES = {"python3-yaml": "yaml", "python3-pytest": "pytest"}
_ALTERNATIVES = {
    "rclcpp": "rclpy (the course's ROS 2 has no C++ client library)",
    "turtlesim": "the course's turtlesim (run `make setup`)",
}
ALL_THERE = "#All required rosdeps installed successfully"
NO_DATABASE = (
    "The course's rosdep needs no database: dependencies come from the course's environment "
    "(environment.txt); `rosdep install --from-paths src -i -y` checks them."
)


def package_manifests(paths: Sequence[Path]) -> Iterator[Path]:
    """Yield every package.xml under `paths`, skipping folders with COLCON_IGNORE."""
    for root in paths:
        for folder, dirs, files in os.walk(root):
            if "COLCON_IGNORE" in files:
                dirs[:] = []
                continue
            dirs[:] = sorted(d for d in dirs if not d.startswith("."))
            if "package.xml" in files:
                dirs[:] = []
                yield Path(folder) / "package.xml"


def _keys(manifest: Path, tags: Sequence[str]) -> list[str]:
    root = ET.parse(manifest).getroot()
    return [e.text.strip() for tag in tags for e in root.iter(tag) if e.text]


def _ros_packages() -> set[str]:
    prefixes = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    found: set[str] = set()
    for prefix in [*prefixes, sys.prefix]:
        index = Path(prefix) / "share" / "ament_index" / "resource_index" / "packages"
        if index.is_dir():
            found.update(p.name for p in index.iterdir())
    return found


def _installed(key: str, ros: set[str]) -> bool:
    if key in ros:
        return True
    if key.startswith("python3-"):
        module = _PYTHON_MODULES.get(key, key.removeprefix("python3-").replace("-", "_"))
        return importlib.util.find_spec(module) is not None
    return False


def missing_keys(manifest: Path, tags: Sequence[str], ignore: set[str]) -> list[str]:
    """Return the dependency keys of `manifest` (of `tags`) that are not installed."""
    ros = _ros_packages()
    keys = dict.fromkeys(_keys(manifest, tags))
    return [k for k in keys if k not in ignore and not _installed(k, ros)]


def _name(manifest: Path) -> str:
    return ET.parse(manifest).getroot().findtext("name", default=manifest.parent.name).strip()


def _install(args: argparse.Namespace) -> int:
    manifests = list(package_manifests([Path(p) for p in args.from_paths]))
    ignore = {_name(m) for m in manifests} if args.ignore_src else set()
    failures, untested = [], []
    for manifest in manifests:
        missing = missing_keys(manifest, _RUN_TAGS, ignore)
        if missing:
            offered = [
                f"{k} (try {_ALTERNATIVES[k]})" if k in _ALTERNATIVES else k for k in missing
            ]
            failures.append(
                f"{_name(manifest)}: not in the course's environment: {', '.join(offered)}"
            )
        untested += missing_keys(manifest, _TEST_TAGS, ignore)
    if failures:
        print(
            "ERROR: the following packages/stacks could not have their rosdep keys resolved "
            "to system dependencies:",
            file=sys.stderr,
        )
        print("\n".join(failures), file=sys.stderr)
        return 1
    print(ALL_THERE)
    if untested:
        print(
            f"(test dependencies not installed, so `colcon test` skips their linters: "
            f"{', '.join(dict.fromkeys(untested))})"
        )
    return 0


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="rosdep", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="store_true", help="print the version and exit")
    parser.add_argument("verb", nargs="?", choices=["install", "check", "init", "update"])
    parser.add_argument("--from-paths", "--from-path", nargs="+", default=[], dest="from_paths")
    parser.add_argument("-i", "--ignore-src", "--ignore-packages-from-source", action="store_true")
    parser.add_argument("--rosdistro")
    parser.add_argument("-y", "--default-yes", action="store_true")
    parser.add_argument("-r", action="store_true", help="continue installing despite errors")
    parser.add_argument("-q", "--quiet", action="store_true")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """`rosdep install|check --from-paths ...`, `rosdep init|update`, `rosdep --version`."""
    args = _parser().parse_args(argv)
    if args.version:
        print("the course's rosdep: checks package.xml dependencies against environment.txt")
        return 0
    if args.verb in ("init", "update"):
        print(NO_DATABASE)
        return 0
    if args.rosdistro and args.rosdistro != os.environ.get("ROS_DISTRO", "jazzy"):
        print(
            f"The course has ROS 2 jazzy, not {args.rosdistro}: use --rosdistro jazzy.",
            file=sys.stderr,
        )
        return 1
    if args.verb is None or not args.from_paths:
        print("Try: rosdep install -i --from-path src --rosdistro $ROS_DISTRO -y", file=sys.stderr)
        return 1
    return _install(args)


if __name__ == "__main__":
    sys.exit(main())
