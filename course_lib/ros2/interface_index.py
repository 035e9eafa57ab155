"""Find the interface files (.msg/.srv/.action) of the installed packages (pure, files only).

Reads the ament index's `rosidl_interfaces` resources under each AMENT_PREFIX_PATH entry
(the course's workspace first) and this interpreter's prefix, where the ROS wheels install
theirs; names and errors as rosidl_runtime_py's get_interfaces/get_interface_path.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path

from ..core import ament_index

__all__ = [
    "KINDS",
    "interface_packages",
    "interface_path",
    "interfaces",
    "prefixes",
]


def _is_msg(name: str) -> bool:
    return name.startswith("msg/") and name[-4:] in (".idl", ".msg")


def _is_srv(name: str) -> bool:
    return name.startswith("srv/") and name[-4:] in (".idl", ".srv")


def _is_action(name: str) -> bool:
    return name.startswith("action/") and (name.endswith(".idl") or name.endswith(".action"))


KINDS: dict[str, Callable[[str], bool]] = {
    "": lambda _name: True,
    "msg": _is_msg,
    "srv": _is_srv,
    "action": _is_action,
}


def prefixes(env: Mapping[str, str]) -> list[Path]:
    """Return the install prefixes to search, first wins: AMENT_PREFIX_PATH, then the wheels'."""
    found = ament_index.prefix_path(env) or []
    return list(dict.fromkeys([*found, Path(sys.prefix)]))


def interface_packages(roots: Iterable[Path]) -> list[str]:
    """Return the packages that generate interfaces, sorted."""
    return sorted(ament_index.resources("rosidl_interfaces", roots))


def interfaces(
    roots: list[Path], packages: Iterable[str] = (), kind: str = ""
) -> dict[str, list[str]]:
    """Return package -> sorted interface names (`msg/Twist`) of one kind ("" for all).

    Raise LookupError("Unknown package 'x'") for a package that is not installed.
    """
    index = ament_index.resources("rosidl_interfaces", roots)
    wanted = list(packages) or list(index)
    known = ament_index.resources("packages", roots)
    keep = KINDS[kind]
    result: dict[str, list[str]] = {}
    for package in wanted:
        if package not in known:
            raise LookupError(f"Unknown package '{package}'")
        if package not in index:
            continue
        lines = ament_index.resource("rosidl_interfaces", package, [index[package]])
        names = {
            line.rsplit(".", 1)[0] for line in lines.splitlines() if "_" not in line and keep(line)
        }
        if names:
            result[package] = sorted(names)
    return result


def interface_path(name: str, roots: list[Path]) -> Path:
    """Return the file of `pkg/msg/Name` (.msg/.srv/.action, else .idl), as ros2 finds it."""
    parts = name.split("/")
    if len(parts) < 2:
        raise ValueError(f"Invalid name '{name}'. Expected at least two parts separated by '/'")
    if not all(parts):
        raise ValueError(f"Invalid name '{name}'. Must not contain empty parts")
    if ".." in parts:
        raise ValueError(f"Invalid name '{name}'. Must not contain '..'")
    prefix = ament_index.resources("packages", roots).get(parts[0])
    if prefix is None:
        raise LookupError(f"Unknown package '{parts[0]}'")
    path = os.path.join(prefix, "share", name)
    if len(parts[-1].rsplit(".", 1)) == 1:
        with_suffix = f"{path}.{parts[-2]}"
        if os.path.exists(with_suffix):
            return Path(with_suffix)
        path += ".idl"
    if not os.path.exists(path):
        raise LookupError(f"Could not find the interface '{path}'")
    return Path(path)
