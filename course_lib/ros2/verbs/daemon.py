"""`ros2 daemon start|stop|status`: the course's per-domain daemon, in ros2cli's words."""

from __future__ import annotations

import argparse
import os
from typing import Any

from ..node.connect import daemon_running, start_detached, stop_daemon
from ..verbkit.context import Context
from ..verbkit.registry import command, verb

__all__ = ["daemon_start", "daemon_start_arguments", "daemon_status", "daemon_stop"]

NO_DOMAIN = (
    "ros2 daemon: this shell sets no ROS_DOMAIN_ID and no course lab is running, so the "
    "course's ros2 commands use no daemon here (each one runs in a private domain). "
    "Start the lab (`make lab`) or set ROS_DOMAIN_ID to the domain your nodes use."
)
NO_DEBUG = (
    "`ros2 daemon start --debug` is not part of this course's ros2 commands (the course's "
    "daemon prints nothing); use `ros2 daemon start`, then `ros2 daemon status`."
)


command("daemon", "Various daemon related sub-commands")


def _domain(ctx: Context) -> str | None:
    return (ctx.env.get("ROS_DOMAIN_ID") or os.environ.get("ROS_DOMAIN_ID") or "").strip() or None


@verb("daemon", "status", "Output the status of the daemon", graph=False)
def daemon_status(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 daemon status`."""
    domain = _domain(ctx)
    running = domain is not None and daemon_running(domain)
    ctx.console.out("The daemon is running\n" if running else "The daemon is not running\n")
    return 0


def daemon_start_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 daemon start`."""
    parser.add_argument("--debug", "-d", action="store_true", help="Print debug messages")


@verb(
    "daemon",
    "start",
    "Start the daemon if it isn't running",
    arguments=daemon_start_arguments,
    graph=False,
)
def daemon_start(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 daemon start`: start this domain's daemon unless it runs."""
    domain = _domain(ctx)
    if domain is None:
        return NO_DOMAIN
    if args.debug:
        return NO_DEBUG
    if ctx.env:
        env = dict(ctx.env)
    else:  # a notebook cell: the kernel's session environment
        from ...session.session import session_env

        env = session_env(int(domain), os.environ)
    env["ROS_DOMAIN_ID"] = domain
    started = start_detached(env)
    ctx.console.out(
        "The daemon has been started\n" if started else "The daemon is already running\n"
    )
    return 0


@verb("daemon", "stop", "Stop the daemon if it is running", graph=False)
def daemon_stop(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 daemon stop`: stop this domain's daemon and wait until it is gone."""
    domain = _domain(ctx)
    try:
        stopped = domain is not None and stop_daemon(domain)
    except TimeoutError as exc:
        return str(exc)
    ctx.console.out("The daemon has been stopped\n" if stopped else "The daemon is not running\n")
    return 0
