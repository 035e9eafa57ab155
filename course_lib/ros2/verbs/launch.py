"""`ros2 launch ...`: handed to course_lib.launch, which parses its own arguments and prints."""

from __future__ import annotations

import os
from collections.abc import Mapping

from ..verbkit.context import Context
from ..verbkit.registry import raw_command

__all__ = ["launch_env", "main"]

_PREFIXES = "AMENT_PREFIX_PATH"


def launch_env(argv: list[str], caller: Mapping[str, str], underlaid: Mapping[str, str]) -> dict:
    """Return the environment `ros2 launch <argv>` runs with.

    The course's workspace is underlaid (its packages launch from any terminal), unless the
    package is found nowhere: then the caller's own AMENT_PREFIX_PATH, so that "not found"
    lists the prefixes the caller's environment names, as the real tool's message does.
    """
    env = dict(underlaid)
    if not caller.get(_PREFIXES):
        return env
    try:
        from ...core.ament import package_prefix
        from ...core.errors import PackageNotFoundError
        from ...launch.command.cli import build_parser

        args, _rest = build_parser().parse_known_args(argv)
    except (ImportError, SystemExit):
        return env  # launch itself says what is wrong with the command line
    if os.path.isfile(args.package_name):
        return env
    try:
        package_prefix(args.package_name, underlaid)
    except PackageNotFoundError:
        env[_PREFIXES] = caller[_PREFIXES]
    return env


@raw_command("launch", "Run a launch file")
def main(argv: list[str], ctx: Context) -> int:
    """Run `ros2 launch <argv>` (it prints straight to this process)."""
    try:
        from ...launch.command import cli as launch_cli
    except ImportError as exc:
        ctx.console.err(f"ros2 launch is not available in this course yet ({exc}).\n")
        return 1
    return int(launch_cli.main(argv) or 0)
