"""`ros2 topic echo` and `ros2 topic hz` on the shared client node, stoppable from any door."""

from __future__ import annotations

import argparse
import math
import queue
import time
from typing import Any

from ..msgcsv import message_to_csv
from ..msgyaml import message_to_yaml
from ..node.client import YOUNG_CLIENT_S
from ..verbkit import options
from ..verbkit.context import Context
from ..verbkit.registry import verb
from ..verbkit.topic_types import expand_topic, import_message, message_class, type_of

__all__ = [
    "topic_echo",
    "topic_echo_arguments",
    "topic_hz",
    "topic_hz_arguments",
]

_TICK_S = 0.1


_OVERRIDES = (
    "qos_reliability",
    "qos_durability",
    "qos_depth",
    "qos_history",
    "qos_liveliness",
    "qos_liveliness_lease_duration_seconds",
)


def _qos(ctx: Context, topic: str, args: argparse.Namespace) -> Any:
    if any(getattr(args, name, None) is not None for name in _OVERRIDES):
        from ..node.qos import qos_from_args

        return qos_from_args(args)
    from rclpy.qos import QoSDurabilityPolicy, QoSReliabilityPolicy

    from ..node.qos import preset

    profile = preset(getattr(args, "qos_profile", "sensor_data"))
    infos = ctx.client.node.get_publishers_info_by_topic(topic)
    if infos:
        reliable = sum(i.qos_profile.reliability == QoSReliabilityPolicy.RELIABLE for i in infos)
        durable = sum(
            i.qos_profile.durability == QoSDurabilityPolicy.TRANSIENT_LOCAL for i in infos
        )
        profile.reliability = (
            QoSReliabilityPolicy.RELIABLE
            if reliable == len(infos)
            else QoSReliabilityPolicy.BEST_EFFORT
        )
        profile.durability = (
            QoSDurabilityPolicy.TRANSIENT_LOCAL
            if durable == len(infos)
            else QoSDurabilityPolicy.VOLATILE
        )
    return profile


def _resolve(ctx: Context, args: argparse.Namespace) -> Any:
    if args.message_type is not None:
        try:
            return message_class(args.message_type)
        except (AttributeError, ModuleNotFoundError, ValueError):
            raise RuntimeError("The passed message type is invalid") from None
    type_name = type_of(ctx, args.topic_name)
    if type_name is None:
        ctx.console.out(
            f"WARNING: topic [{args.topic_name}] does not appear to be published yet\n"
        )
        raise RuntimeError("Could not determine the type for the passed topic")
    return import_message(type_name)


def _field(msg: Any, path: list[str]) -> Any:
    for name in path:
        try:
            msg = getattr(msg, name)
        except AttributeError as exc:
            raise RuntimeError(f"Invalid field '{'.'.join(path)}': {exc}") from None
    return msg


def _format(msg: Any, info: Any, args: argparse.Namespace) -> str:
    """Return what ros2topic prints for one message: a raw or non-message value as is, else
    one CSV line or YAML (each with its message info first when asked)."""
    if not hasattr(msg, "__slots__"):
        head = ""
        if args.include_message_info:
            head = f"---Got new message, message info:---\n{dict(info)}\n---Message data:---\n"
        return f"{head}{msg}\n---\n"
    limit = None if args.full_length else args.truncate_length
    if args.csv:
        line = message_to_csv(msg, truncate_length=limit, no_arr=args.no_arr, no_str=args.no_str)
        if args.include_message_info:
            line = ",".join(str(x) for x in dict(info).values()) + "," + line
        return line + "\n"
    head = _info_text(info) if args.include_message_info else ""
    return head + (
        message_to_yaml(
            msg,
            truncate_length=limit,
            no_arr=args.no_arr,
            no_str=args.no_str,
            flow_style=args.flow_style,
        )
        + "---\n"
    )


def _filter(expr: str | None) -> Any:
    """Return ros2topic's `--filter` predicate over `m` (the learner's own expression)."""
    if not expr:
        return None
    code = compile(expr, "<filter>", "eval")
    return lambda m: eval(code, {}, {"m": m})


def _lost(ctx: Context) -> Any:
    from rclpy.event_handler import SubscriptionEventCallbacks

    def report(status: Any) -> None:
        ctx.console.out(
            "A message was lost!!!\n\ttotal count change:"
            f"{status.total_count_change}\n\ttotal count: {status.total_count}---\n"
        )

    return SubscriptionEventCallbacks(message_lost=report)


def topic_echo_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 topic echo`."""
    options.strategy(parser)
    parser.add_argument("topic_name", help="Name of the ROS topic to listen to (e.g. '/chatter')")
    parser.add_argument(
        "message_type", nargs="?", help="Type of the ROS message (e.g. 'std_msgs/msg/String')"
    )
    options.qos(parser, "subscribe", "sensor_data")
    parser.add_argument(
        "--csv",
        action="store_true",
        help="Output all recursive fields separated by commas (e.g. for plotting). If "
        "--include-message-info is also passed, the following fields are prepended: "
        "source_timestamp, received_timestamp, publication_sequence_number, "
        "reception_sequence_number.",
    )
    parser.add_argument(
        "--field",
        type=str,
        default=None,
        help="Echo a selected field of a message. Use '.' to select sub-fields. For example, to "
        "echo the position field of a nav_msgs/msg/Odometry message: 'ros2 topic echo "
        "/odom --field pose.pose.position'",
    )
    parser.add_argument(
        "--full-length",
        "-f",
        action="store_true",
        help="Output all elements for arrays, bytes, and string with a length > "
        "'--truncate-length', by default they are truncated after '--truncate-length' "
        "elements with '...''",
    )
    parser.add_argument(
        "--truncate-length",
        "-l",
        type=options.unsigned_int,
        default=128,
        help="The length to truncate arrays, bytes, and string to (default: 128)",
    )
    parser.add_argument(
        "--no-arr", action="store_true", help="Don't print array fields of messages"
    )
    parser.add_argument(
        "--no-str", action="store_true", help="Don't print string fields of messages"
    )
    parser.add_argument(
        "--flow-style",
        action="store_true",
        help="Print collections in the block style (not available with csv format)",
    )
    parser.add_argument(
        "--no-lost-messages", action="store_true", help="Don't report when a message is lost"
    )
    parser.add_argument("--raw", action="store_true", help="Echo the raw binary representation")
    parser.add_argument(
        "--filter",
        dest="filter_expr",
        help="Python expression to filter messages that are printed. Expression can use Python "
        "builtins as well as m (the message).",
    )
    parser.add_argument(
        "--once", action="store_true", help="Print the first message received and then exit."
    )
    parser.add_argument(
        "--timeout",
        metavar="N",
        type=options.positive_float,
        help="Set a timeout in seconds for waiting",
        default=None,
    )
    parser.add_argument(
        "--include-message-info",
        "-i",
        action="store_true",
        help="Shows the associated message info.",
    )


@verb("topic", "echo", "Output messages from a topic", arguments=topic_echo_arguments)
def topic_echo(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 topic echo <topic> [type] [--once] [--field F] [--timeout N] [--filter E] [-i]`."""
    if args.use_sim_time and args.timeout:
        return "`ros2 topic echo --use-sim-time --timeout` is not part of this course."
    keep = _filter(args.filter_expr)
    path = None
    if args.field is not None:
        path = [p for p in args.field.split(".") if p]
        if not path:
            return f"Invalid field value '{args.field}'"
    msg_class = _resolve(ctx, args)
    topic = expand_topic(args.topic_name)
    inbox: queue.Queue[Any] = queue.Queue()
    node = ctx.client.node
    events = None if args.no_lost_messages else _lost(ctx)
    sub = node.create_subscription(
        msg_class,
        topic,
        lambda msg, info: inbox.put((msg, info)),
        _qos(ctx, topic, args),
        event_callbacks=events,
        raw=args.raw,
    )
    deadline = time.monotonic() + args.timeout if args.timeout else math.inf
    try:
        while not ctx.console.cancelled.is_set() and time.monotonic() < deadline:
            try:
                msg, info = inbox.get(timeout=min(_TICK_S, max(0.0, deadline - time.monotonic())))
            except queue.Empty:
                continue
            shown = _field(msg, path) if path else msg
            if keep is not None and not keep(shown):
                continue
            ctx.console.out(_format(shown, info, args))
            if args.once:
                break
    finally:
        node.destroy_subscription(sub)
    return 2 if ctx.console.cancelled.is_set() else 0  # Ctrl-C: ros2cli's exit code


def _info_text(info: Any) -> str:
    import yaml

    return yaml.dump(dict(info)) + "---\n"


def _hz_line(times: list[float]) -> str:
    n = len(times)
    mean = sum(times) / n
    rate = 1.0 / mean if mean > 0 else 0.0
    std = math.sqrt(sum((x - mean) ** 2 for x in times) / n)
    return (
        f"average rate: {rate:.3f}\n\tmin: {min(times):.3f}s max: {max(times):.3f}s "
        f"std dev: {std:.5f}s window: {n}\n"
    )


def topic_hz_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 topic hz`."""
    parser.add_argument("topic_name", help="Name of the ROS topic to listen to (e.g. '/chatter')")
    parser.add_argument(
        "--window",
        "-w",
        dest="window_size",
        type=options.positive_int,
        default=10000,
        help="window size, in # of messages, for calculating rate (default: 10000)",
        metavar="WINDOW",
    )
    parser.add_argument(
        "--filter",
        dest="filter_expr",
        default=None,
        help="only measure messages matching the specified Python expression",
        metavar="EXPR",
    )
    parser.add_argument(
        "--wall-time",
        dest="use_wtime",
        default=False,
        action="store_true",
        help="calculates rate using wall time which can be helpful when clock is not published "
        "during simulation",
    )
    options.direct(parser)


@verb("topic", "hz", "Print the average publishing rate to screen", arguments=topic_hz_arguments)
def topic_hz(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 topic hz <topic> [--window N] [--filter E] [--wall-time]`: rate each second.

    The course's client node runs on wall time, so the rate is wall time with or without
    `--wall-time` (as the real tool's without simulated time).
    """
    from rclpy.qos import qos_profile_sensor_data

    if args.use_sim_time:
        return "`ros2 topic hz --use-sim-time` is not part of this course: it measures wall time."
    keep = _filter(args.filter_expr)
    # hz keeps waiting for a missing topic, so it warns at once (as ros2topic's blocking
    # get_msg_class); only a young client first gives discovery its time.
    young = max(0.0, YOUNG_CLIENT_S - ctx.client.age())
    type_name = type_of(ctx, args.topic_name, wait=young > 0)
    if type_name is None:
        ctx.console.out(
            f"WARNING: topic [{args.topic_name}] does not appear to be published yet\n"
        )
    while type_name is None:
        if ctx.console.cancelled.wait(_TICK_S):
            return 2
        type_name = type_of(ctx, args.topic_name, wait=False)
    stamps: queue.Queue[float] = queue.Queue()
    node = ctx.client.node

    def on_message(message: Any) -> None:
        if keep is None or keep(message):
            stamps.put(time.monotonic())

    sub = node.create_subscription(
        import_message(type_name),
        expand_topic(args.topic_name),
        on_message,
        qos_profile_sensor_data,
    )
    deltas: list[float] = []
    last: float | None = None
    printed = time.monotonic()
    try:
        while not ctx.console.cancelled.wait(_TICK_S):
            while not stamps.empty():
                stamp = stamps.get()
                if last is not None:
                    deltas = [*deltas, stamp - last][-args.window_size :]
                last = stamp
            if deltas and last is not None and last >= printed + 1.0:
                ctx.console.out(_hz_line(deltas))
                printed = last
    finally:
        node.destroy_subscription(sub)
    return 2 if ctx.console.cancelled.is_set() else 0  # Ctrl-C: ros2cli's exit code
