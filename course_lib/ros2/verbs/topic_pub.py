"""`ros2 topic pub <topic> <type> [values]` with ros2topic 0.32.2's options and output."""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import yaml

from ..msgfill import import_type, set_message_fields
from ..node.delivery import keep_until_acknowledged
from ..verbkit import options
from ..verbkit.context import Context
from ..verbkit.registry import verb

__all__ = ["add_arguments", "main"]

WAIT_TICK_S = 0.1


def _nonnegative_int(text: str) -> int:
    value = int(text)
    if value < 0:
        raise ValueError("Value must be positive or zero")
    return value


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 topic pub`."""
    parser.add_argument("topic_name", help="Name of the ROS topic to publish to (e.g. '/chatter')")
    parser.add_argument("message_type", help="Type of the ROS message (e.g. 'std_msgs/String')")
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "values",
        nargs="?",
        default="{}",
        help="Values to fill the message with in YAML format (e.g. 'data: Hello World'), "
        "otherwise the message will be published with default values",
    )
    group.add_argument("--stdin", action="store_true", help="Read values from standard input")
    parser.add_argument(
        "-r",
        "--rate",
        metavar="N",
        type=options.positive_float,
        default=1.0,
        help="Publishing rate in Hz (default: 1)",
    )
    parser.add_argument(
        "-p",
        "--print",
        metavar="N",
        type=int,
        default=1,
        help="Only print every N-th published message (default: 1)",
    )
    group = parser.add_mutually_exclusive_group()
    group.add_argument("-1", "--once", action="store_true", help="Publish one message and exit")
    group.add_argument(
        "-t",
        "--times",
        type=_nonnegative_int,
        default=0,
        help="Publish this number of times and then exit",
    )
    parser.add_argument(
        "-w",
        "--wait-matching-subscriptions",
        type=_nonnegative_int,
        default=None,
        help="Wait until finding the specified number of matching subscriptions. Defaults to 1 "
        'when using "-1"/"--once"/"--times", otherwise defaults to 0.',
    )
    parser.add_argument(
        "--max-wait-time-secs",
        type=options.positive_float,
        default=None,
        help="This sets the maximum wait time in seconds if --wait-until-matching-subscriptions "
        "is set. By default, this flag is not set meaning the subscriber will wait endlessly.",
    )
    parser.add_argument(
        "--keep-alive",
        metavar="N",
        type=options.positive_float,
        default=0.1,
        help="Keep publishing node alive for N seconds after the last msg (default: 0.1)",
    )
    parser.add_argument("-n", "--node-name", help="Name of the created publishing node")
    options.qos(parser, "publish", "default")
    options.direct(parser)


@contextmanager
def _publishing_node(args: argparse.Namespace, ctx: Context) -> Iterator[Any]:
    """Yield the node to publish from: the client node, or one named by -n / using sim time."""
    shared = ctx.client.node
    if args.node_name is None and not args.use_sim_time:
        yield shared
        return
    import rclpy
    from rclpy.parameter import Parameter

    node = rclpy.create_node(
        args.node_name or f"_ros2cli_{os.getpid()}",
        context=shared.context,
        start_parameter_services=False,
        parameter_overrides=[Parameter("use_sim_time", value=bool(args.use_sim_time))],
    )
    try:
        yield node
    finally:
        node.destroy_node()


def _wait_for_subscribers(pub: Any, wanted: int, max_wait: float | None, ctx: Context) -> Any:
    """Wait as ros2topic does (a line each second); return an error text, 2 or None."""
    ticks, waited = 0, 0.0
    while pub.get_subscription_count() < wanted:
        if not ticks:
            ctx.console.out(f"Waiting for at least {wanted} matching subscription(s)...\n")
        if max_wait is not None and max_wait <= waited:
            return (
                f"Timed out waiting for subscribers: Expected {wanted} subcribers but only got "
                f"{pub.get_subscription_count()} subscribers"
            )
        ticks = (ticks + 1) % 10
        if ctx.console.cancelled.wait(WAIT_TICK_S):
            return 2
        waited += WAIT_TICK_S
    return None


@verb("topic", "pub", "Publish a message to a topic", arguments=add_arguments)
def main(args: argparse.Namespace, ctx: Context) -> Any:
    """Publish the message once, N times or at a rate until Ctrl-C."""
    from ..node.qos import qos_from_args

    times = 1 if args.once else args.times
    wanted = args.wait_matching_subscriptions
    wanted = int(times != 0) if wanted is None else wanted
    values = sys.stdin.read() if args.stdin else args.values
    try:
        msg_class = import_type(args.message_type, "msg")
    except (AttributeError, ModuleNotFoundError, ValueError):
        raise RuntimeError("The passed message type is invalid") from None
    mapping = yaml.safe_load(values)
    if not isinstance(mapping, dict):
        return "The passed value needs to be a dictionary in YAML format"
    with _publishing_node(args, ctx) as node:
        pub = node.create_publisher(msg_class, args.topic_name, qos_from_args(args))
        try:
            if wanted == 0 and args.max_wait_time_secs is not None:
                return (
                    "--max-wait-time-secs option is only effective with "
                    "--wait-matching-subscriptions, --once or --times"
                )
            waited = _wait_for_subscribers(pub, wanted, args.max_wait_time_secs, ctx)
            if waited is not None:
                return waited
            return _publish_loop(node, pub, msg_class, mapping, times, args, ctx)
        finally:
            node.destroy_publisher(pub)


def _publish_loop(
    node: Any, pub: Any, msg_class: Any, mapping: dict, times: int, args: Any, ctx: Context
) -> Any:
    msg = msg_class()
    try:
        stamps = set_message_fields(msg, mapping, expand_header_auto=True, expand_time_now=True)
    except Exception as exc:
        return f"Failed to populate field: {exc}"
    ctx.console.out("publisher: beginning loop\n")
    period, count, start = 1.0 / args.rate, 0, time.monotonic()
    while True:
        now = node.get_clock().now().to_msg()
        for setter in stamps:
            setter(now)
        count += 1
        if args.print and count % args.print == 0:
            ctx.console.out(f"publishing #{count}: {msg!r}\n\n")
        pub.publish(msg)
        if times and count >= times:
            break
        if ctx.console.cancelled.wait(max(0.0, start + count * period - time.monotonic())):
            return 2
    keep_until_acknowledged(pub, keep_alive=args.keep_alive)
    return 0
