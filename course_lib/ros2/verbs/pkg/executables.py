"""`ros2 pkg executables|prefix` and `ros2 run`, over the course's ament index (no rclpy)."""

from __future__ import annotations

import argparse
import os
import shlex
import signal
from pathlib import Path
from typing import Any

from ....core import ament, param_journal
from ....core.errors import PackageNotFoundError
from ...verbkit.context import Context
from ...verbkit.registry import command_verb, verb
from .absent_programs import absent_program_hint

__all__ = [
    "executable_paths",
    "pkg_executables",
    "pkg_executables_arguments",
    "pkg_prefix",
    "pkg_prefix_arguments",
    "run",
    "run_arguments",
]

RUN_PREFIX = "[ros2run]:"


def _env(ctx: Context) -> dict[str, str]:
    return dict(ctx.env) if ctx.env else ament.workspace_env()


def executable_paths(package: str, env: dict[str, str]) -> list[Path]:
    """Return every executable file under `<prefix>/lib/<package>`, as ros2pkg walks it."""
    base = ament.package_prefix(package, env) / "lib" / package
    paths: list[Path] = []
    for dirpath, dirnames, filenames in os.walk(base):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
        for filename in sorted(filenames):
            path = Path(dirpath) / filename
            if os.access(path, os.X_OK):
                paths.append(path)
    return paths


def pkg_executables_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 pkg executables`."""
    parser.add_argument("package_name", nargs="?", help="The package name")
    parser.add_argument(
        "--full-path", action="store_true", default=False, help="Show full path of each executable"
    )


@verb(
    "pkg",
    "executables",
    "Output a list of package specific executables",
    arguments=pkg_executables_arguments,
    graph=False,
)
def pkg_executables(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 pkg executables [package] [--full-path]`."""
    env = _env(ctx)
    packages = [args.package_name] if args.package_name else list(ament.list_packages(env))
    lines = []
    for package in sorted(packages):
        try:
            paths = executable_paths(package, env)
        except PackageNotFoundError:
            return f"Package '{args.package_name}' not found"
        for path in sorted(str(p) for p in paths):
            lines.append(path if args.full_path else f"{package} {os.path.basename(path)}")
    ctx.console.out("".join(f"{line}\n" for line in lines))
    return 0


def pkg_prefix_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 pkg prefix`."""
    parser.add_argument("package_name", help="The package name")
    parser.add_argument(
        "--share", action="store_true", help="Show share directory for the package"
    )


@verb(
    "pkg",
    "prefix",
    "Output the prefix path of a package",
    arguments=pkg_prefix_arguments,
    graph=False,
)
def pkg_prefix(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 pkg prefix <package> [--share]`."""
    try:
        prefix = ament.package_prefix(args.package_name, _env(ctx))
    except PackageNotFoundError:
        return "Package not found"
    path = prefix / "share" / args.package_name if args.share else prefix
    ctx.console.out(f"{path}\n")
    return 0


def _find(args: argparse.Namespace, env: dict[str, str]) -> Path | str:
    """Return the executable's path, or the message ros2run fails with."""
    hint = absent_program_hint(args.package_name, args.executable_name)
    try:
        paths = executable_paths(args.package_name, env)
    except PackageNotFoundError:
        return hint or f"Package '{args.package_name}' not found"
    matches = [p for p in paths if p.name == args.executable_name]
    if not matches:
        return hint or "No executable found"
    if len(matches) > 1:
        return "Multiple executables found:" + "".join(f"\n- {p}" for p in matches)
    return matches[0]


def _report_exit(code: int, ctx: Context) -> None:
    if code == 0:
        return
    if code < 0 and -code in {int(s) for s in signal.valid_signals()}:
        ctx.console.out(f"{RUN_PREFIX} {signal.strsignal(-code)}\n")
    else:
        ctx.console.out(f"{RUN_PREFIX} Process exited with failure {code}\n")


def run_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 run`."""
    parser.add_argument(
        "--prefix",
        help="Prefix command, which should go before the executable. Command must be wrapped in "
        "quotes if it contains spaces (e.g. --prefix 'gdb -ex run --args').",
    )
    parser.add_argument("package_name", help="Name of the ROS package")
    parser.add_argument("executable_name", help="Name of the executable")
    parser.add_argument(
        "argv", nargs=argparse.REMAINDER, help="Pass arbitrary arguments to the executable"
    )


@command_verb("run", "Run a package specific executable", arguments=run_arguments, graph=False)
def run(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 run <package> <executable> [args...]`: in a terminal, in the foreground."""
    env = _env(ctx)
    found = _find(args, env)
    if isinstance(found, str):
        return found
    cmd = [str(found), *args.argv]
    if args.prefix is not None:
        cmd = shlex.split(args.prefix) + cmd
    domain, argv = env.get("ROS_DOMAIN_ID"), list(args.argv)
    starter = getattr(ctx, "background_run", None)
    if starter is not None:  # a notebook's: the node's name is learnt from its log
        param_journal.record_start(domain, args.executable_name, argv, cwd=ctx.cwd)
        return starter(cmd, args.executable_name, ctx)
    from ....processes.children import spawn

    child = spawn(
        cmd, name=args.executable_name, env=env, cwd=ctx.cwd, new_session=False, capture=False
    )
    # a terminal's: the log goes to the terminal; the history names the node by this pid
    param_journal.record_start(domain, args.executable_name, argv, cwd=ctx.cwd, pid=child.pid)
    code: int | None = None
    while code is None:
        try:
            code = child.wait()
        except KeyboardInterrupt:
            continue  # the child got the same Ctrl-C and is shutting down
    _report_exit(code, ctx)
    return code
