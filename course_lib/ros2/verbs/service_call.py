"""`ros2 service call <service> <type> [values] [-r RATE]` (ros2service 0.32.2's output)."""

from __future__ import annotations

import argparse
import sys
import threading
import time
from typing import Any

import yaml

from ..msgfill import import_type, set_message_fields
from ..verbkit.context import Context
from ..verbkit.registry import verb

__all__ = ["add_arguments", "main"]

_POLL_S = 0.05


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 service call`."""
    parser.add_argument(
        "service_name", help="Name of the ROS service to call to (e.g. '/add_two_ints')"
    )
    parser.add_argument("service_type", help="Type of the ROS service (e.g. 'std_srvs/srv/Empty')")
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "values",
        nargs="?",
        default="{}",
        help="Values to fill the service request with in YAML format (e.g. '{a: 1, b: 2}'), "
        "otherwise the service request will be published with default values",
    )
    group.add_argument("--stdin", action="store_true", help="Read values from standard input")
    parser.add_argument(
        "-r", "--rate", metavar="N", type=float, help="Repeat the call at a specific rate in Hz"
    )


def service_class(type_name: str) -> Any:
    """Return the service class of `pkg/srv/Name`, or raise the real tool's RuntimeError."""
    try:
        srv = import_type(type_name, "srv")
    except (AttributeError, ModuleNotFoundError, ValueError):
        raise RuntimeError("The passed service type is invalid") from None
    if not (hasattr(srv, "Request") and hasattr(srv, "Response")):
        raise RuntimeError("The passed type is not a service")
    return srv


def _wait_for_server(cli: Any, ctx: Context) -> bool:
    """Wait without a time limit (as the real tool) until the server is there or Ctrl-C."""
    if cli.service_is_ready():
        return True
    ctx.console.out("waiting for service to become available...\n")
    while not cli.service_is_ready():
        if ctx.console.cancelled.wait(_POLL_S):
            return False
    return True


@verb("service", "call", "Call a service", arguments=add_arguments)
def main(args: argparse.Namespace, ctx: Context) -> Any:
    """Fill the request from YAML, wait for the server, call (at --rate), print both."""
    if args.rate is not None and args.rate <= 0:
        raise RuntimeError("rate must be greater than zero")
    period = 1.0 / args.rate if args.rate else None
    values = sys.stdin.read() if args.stdin else args.values
    srv = service_class(args.service_type)
    mapping = yaml.safe_load(values)
    request = srv.Request()
    try:
        set_message_fields(request, mapping)
    except Exception as exc:
        return f"Failed to populate field: {exc}"
    node = ctx.client.node
    cli = node.create_client(srv, args.service_name)
    try:
        if not _wait_for_server(cli, ctx):
            return 2
        while True:
            ctx.console.out(f"requester: making request: {request!r}\n\n")
            last_call = time.monotonic()
            response = _call(cli, request, ctx)
            if response is None:
                return 2
            ctx.console.out(f"response:\n{response!r}\n\n")
            if period is None:
                return 0
            if ctx.console.cancelled.wait(max(0.0, last_call + period - time.monotonic())):
                return 2
    finally:
        node.destroy_client(cli)


def _call(cli: Any, request: Any, ctx: Context) -> Any:
    """Send the request once (never re-sent: it may be a write) and wait for its reply."""
    done = threading.Event()
    future = cli.call_async(request)
    future.add_done_callback(lambda _f: done.set())
    while not done.wait(_POLL_S):
        if ctx.console.cancelled.is_set():
            cli.remove_pending_request(future)
            return None
    if future.result() is None:
        raise RuntimeError(f"Exception while calling service: {future.exception()!r}")
    return future.result()
