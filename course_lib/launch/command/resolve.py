"""Where `ros2 launch` finds the file, and how it reads `name:=value` arguments."""

from __future__ import annotations

import os

from ament_index_python.packages import PackageNotFoundError, get_package_share_directory

__all__ = [
    "LaunchCommandError",
    "parse_launch_arguments",
    "resolve_launch_file",
    "share_file_path",
]


class LaunchCommandError(RuntimeError):
    """A failure ros2cli reports as one line on stderr with exit code 1."""


def share_file_path(package: str, file_name: str | None) -> str:
    """Return the one file called `file_name` below the package's share folder."""
    share = get_package_share_directory(package)
    matches = [
        os.path.join(root, name)
        for root, _dirs, files in os.walk(share)
        for name in files
        if name == file_name
    ]
    if not matches:
        raise LaunchCommandError(
            f"file '{file_name}' was not found in the share directory of package "
            f"'{package}' which is at '{share}'"
        )
    if len(matches) > 1:
        listing = ", ".join(f"'{m}'" for m in matches)
        raise LaunchCommandError(
            f"file '{file_name}' was found more than once in the share directory of package "
            f"'{package}': [{listing}]"
        )
    return matches[0]


def resolve_launch_file(
    package_name: str, launch_file_name: str | None, launch_arguments: list[str]
) -> tuple[str, list[str]]:
    """Return (path, launch arguments) as `ros2 launch` reads its positional arguments."""
    if os.path.isfile(package_name):
        extra = [] if launch_file_name is None else [launch_file_name]
        return package_name, [*extra, *launch_arguments]
    try:
        return share_file_path(package_name, launch_file_name), list(launch_arguments)
    except PackageNotFoundError as exc:
        raise LaunchCommandError(f"Package '{package_name}' not found: {exc}") from None


def parse_launch_arguments(arguments: list[str]) -> list[tuple[str, str]]:
    """Parse `name:=value` pairs (last one wins), rejecting malformed ones like ros2launch."""
    parsed: dict[str, str] = {}
    for argument in arguments:
        count = argument.count(":=")
        if count == 0 or argument.startswith(":=") or (count == 1 and argument.endswith(":=")):
            raise LaunchCommandError(
                f"malformed launch argument '{argument}', expected format '<name>:=<value>'"
            )
        name, value = argument.split(":=", maxsplit=1)
        parsed[name] = value
    return list(parsed.items())
