"""`ros2 launch`: the console command (the `ros2` dispatcher calls `main(argv)`)."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import os
import sys

from ..api.actions import IncludeLaunchDescription
from ..core.description import AnyLaunchDescriptionSource, LaunchDescription
from ..ros.parameters import WRITTEN_FILES
from ..runtime.screen import LaunchLog
from ..runtime.service import Runtime
from ..runtime.shim import launch_modules
from .describe import print_arguments_of_launch_file
from .dry_run import dry_run_file
from .resolve import LaunchCommandError, parse_launch_arguments, resolve_launch_file

__all__ = [
    "LaunchCommandError",
    "build_parser",
    "main",
    "parse_launch_arguments",
    "resolve_launch_file",
]


def build_parser() -> argparse.ArgumentParser:
    """Return the argument parser of `ros2 launch` (plus the course's `--dry-run`)."""
    parser = argparse.ArgumentParser(prog="ros2 launch", description="Run a launch file")
    parser.add_argument(
        "-n",
        "--noninteractive",
        default=not sys.stdin.isatty(),
        action="store_true",
        help="Run the launch system non-interactively, with no terminal associated",
    )
    parser.add_argument(
        "-d",
        "--debug",
        default=False,
        action="store_true",
        help="Put the launch system in debug mode, provides more verbose output.",
    )
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "-p",
        "--print",
        "--print-description",
        default=False,
        action="store_true",
        help="Print the launch description to the console without launching it.",
    )
    group.add_argument(
        "-s",
        "--show-args",
        "--show-arguments",
        default=False,
        action="store_true",
        help="Show arguments that may be given to the launch file.",
    )
    group.add_argument(
        "--dry-run",
        default=False,
        action="store_true",
        help="(course) Show each node's parameters and where they come from, without launching.",
    )
    parser.add_argument(
        "-a",
        "--show-all-subprocesses-output",
        default=False,
        action="store_true",
        help="Show all launched subprocesses' output by overriding their output "
        "configuration using the OVERRIDE_LAUNCH_PROCESS_OUTPUT envvar.",
    )
    parser.add_argument(
        "package_name", help="Name of the ROS package which contains the launch file"
    )
    parser.add_argument("launch_file_name", nargs="?", help="Name of the launch file")
    parser.add_argument(
        "launch_arguments",
        nargs="*",
        help="Arguments to the launch file; '<name>:=<value>' (for duplicates, last one wins)",
    )
    return parser


def run_launch_file(path: str, arguments: list[str], *, noninteractive: bool) -> int:
    """Launch the file until it ends or is interrupted; return launch's exit code."""
    pairs = parse_launch_arguments(arguments)
    with launch_modules():
        out = LaunchLog()
        try:
            runtime = Runtime(out, argv=arguments, noninteractive=noninteractive)
            description = LaunchDescription(
                [
                    IncludeLaunchDescription(
                        AnyLaunchDescriptionSource(path), launch_arguments=pairs
                    )
                ]
            )
            return asyncio.run(runtime.run(description))
        finally:
            out.close()
            _remove_params_files()


def _remove_params_files() -> None:
    """Remove the temporary params files this launch wrote (real launch leaves them)."""
    for name in WRITTEN_FILES:
        with contextlib.suppress(OSError):
            os.remove(name)
    WRITTEN_FILES.clear()


def _dispatch(args: argparse.Namespace) -> int:
    path, arguments = resolve_launch_file(
        args.package_name, args.launch_file_name, list(args.launch_arguments)
    )
    if args.show_all_subprocesses_output:
        os.environ["OVERRIDE_LAUNCH_PROCESS_OUTPUT"] = "both"
    if args.show_args:
        return print_arguments_of_launch_file(path)
    if args.dry_run:
        print(dry_run_file(path, parse_launch_arguments(arguments)).render(), end="")
        return 0
    if args.print:
        raise LaunchCommandError("--print is not supported by the course's ros2 launch")
    return run_launch_file(path, arguments, noninteractive=args.noninteractive)


def main(argv: list[str]) -> int:
    """Run `ros2 launch <argv...>`; return the exit code."""
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:
        return int(exc.code or 0)
    try:
        return _dispatch(args)
    except LaunchCommandError as exc:
        print(str(exc), file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 2
