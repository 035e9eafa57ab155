"""`ros2 topic list|info [-v]|type|find [-c]|bw` (ros2topic 0.32.2's arguments and output)."""

from __future__ import annotations

import argparse
import queue
import threading
import time
from typing import Any

from .. import render
from ..node.discovery import NAME_WAIT_S, UNKNOWN_NODE
from ..node.graph import topics, types_of
from ..verbkit import options
from ..verbkit.context import Context, settled_client
from ..verbkit.registry import command, verb

__all__ = [
    "bw",
    "bw_arguments",
    "delay",
    "delay_arguments",
    "find",
    "find_arguments",
    "info",
    "info_arguments",
    "topic_command_arguments",
    "topic_list",
    "topic_list_arguments",
    "type_",
    "type_arguments",
]

Parser = argparse.ArgumentParser
_POLL_S = 0.1


def info_arguments(parser: Parser) -> None:
    """Arguments of `ros2 topic info`."""
    options.strategy(parser)
    parser.add_argument("topic_name", help="Name of the ROS topic to get info (e.g. '/chatter')")
    parser.add_argument(
        "--verbose",
        "-v",
        action="store_true",
        help="Prints detailed information like the node name, node namespace, topic type, "
        "topic type hash, GUID, and QoS Profile of the publishers and subscribers to this topic",
    )


def type_arguments(parser: Parser) -> None:
    """Arguments of `ros2 topic type`."""
    options.strategy(parser)
    parser.add_argument("topic_name", help="Name of the ROS topic to get type (e.g. '/chatter')")


def find_arguments(parser: Parser) -> None:
    """Arguments of `ros2 topic find`."""
    options.strategy(parser)
    parser.add_argument(
        "topic_type",
        help="Name of the ROS topic type to filter for (e.g. 'std_msg/msg/String')",
    )
    parser.add_argument(
        "-c",
        "--count-topics",
        action="store_true",
        help="Only display the number of topics discovered",
    )
    parser.add_argument(
        "--include-hidden-topics", action="store_true", help="Consider hidden topics as well"
    )


def bw_arguments(parser: Parser) -> None:
    """Arguments of `ros2 topic bw`."""
    parser.add_argument("topic", help="Topic name to monitor for bandwidth utilization")
    parser.add_argument(
        "--window",
        "-w",
        type=options.positive_int,
        default=100,
        help="maximum window size, in # of messages, for calculating rate (default: 100)",
        metavar="WINDOW",
    )
    options.direct(parser)


def _all_named(node: Any, name: str) -> bool:
    infos = [*node.get_publishers_info_by_topic(name), *node.get_subscriptions_info_by_topic(name)]
    return all(info.node_name != UNKNOWN_NODE for info in infos)


@verb("topic", "info", "Print information about a topic", arguments=info_arguments)
def info(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 topic info <topic> [-v]`."""
    types = types_of(ctx.client, args.topic_name, include_hidden=True)
    if types is None:
        return f"Unknown topic '{args.topic_name}'"
    node, name = ctx.client.node, args.topic_name
    if args.verbose:  # an endpoint seen before its node's name: the name follows
        from ...core.waiting import wait_until  # rclpy: only where the command really runs

        wait_until(lambda: _all_named(node, name), NAME_WAIT_S)
    end = "\n\n" if args.verbose else "\n"
    out = [f"Type: {types[0] if len(types) == 1 else types}{end}"]
    out.append(f"Publisher count: {node.count_publishers(name)}{end}")
    if args.verbose:
        out += [f"{endpoint}{end}" for endpoint in node.get_publishers_info_by_topic(name)]
    out.append(f"Subscription count: {node.count_subscribers(name)}{end}")
    if args.verbose:
        out += [f"{endpoint}{end}" for endpoint in node.get_subscriptions_info_by_topic(name)]
    ctx.console.out("".join(out))
    return 0


@verb("topic", "type", "Print a topic's type", arguments=type_arguments)
def type_(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 topic type <topic>`: its type(s), or exit 1 silently."""
    types = types_of(ctx.client, args.topic_name, include_hidden=args.include_hidden_topics)
    if types is None:
        return 1
    ctx.console.out("".join(f"{t}\n" for t in types))
    return 0


@verb(
    "topic", "find", "Output a list of available topics of a given type", arguments=find_arguments
)
def find(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 topic find <type> [-c]`."""
    ctx.client.settle()
    found = topics(ctx.client, include_hidden=args.include_hidden_topics)
    names = [name for name, types in found if args.topic_type in types]
    text = f"{len(names)}\n" if args.count_topics else "".join(f"{n}\n" for n in names)
    ctx.console.out(text)
    return 0


def _size(num: float, unit: str) -> str:
    return {"B": f"{num:.0f} B", "KB": f"{num / 1e3:.2f} KB", "MB": f"{num / 1e6:.2f} MB"}[unit]


def bw_line(sizes: list[int], span_s: float) -> str:
    """Return the two lines `ros2 topic bw` prints for a window of message sizes (pure)."""
    total = sum(sizes)
    per_s = total / span_s
    unit = "B" if per_s < 1e3 else "KB" if per_s < 1e6 else "MB"
    mean, low, high = total / len(sizes), min(sizes), max(sizes)
    return (
        f"{_size(per_s, unit)}/s from {len(sizes)} messages\n"
        f"\tMessage size mean: {_size(mean, unit)} min: {_size(low, unit)} "
        f"max: {_size(high, unit)}\n"
    )


def _wait_for_type(ctx: Context, topic: str) -> str | None:
    types = types_of(ctx.client, topic, include_hidden=True)
    if types is not None:
        return types[0]
    ctx.console.out(f"WARNING: topic [{topic}] does not appear to be published yet\n")
    while not ctx.console.cancelled.wait(_POLL_S):
        types = dict(topics(ctx.client, include_hidden=True)).get(topic)
        if types:
            return types[0]
    return None


@verb("topic", "bw", "Display bandwidth used by topic", arguments=bw_arguments)
def bw(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 topic bw <topic> [-w N]`: serialized bytes per second, printed each second."""
    if args.use_sim_time:
        return "`ros2 topic bw --use-sim-time` is not part of this course: it measures wall time."
    from rclpy.qos import qos_profile_sensor_data

    from ..verbkit.topic_types import import_message

    type_name = _wait_for_type(ctx, args.topic)
    if type_name is None:
        return 2
    msg_class = import_message(type_name)  # one this environment lacks: ros2topic's error
    lock = threading.Lock()
    window: list[tuple[float, int]] = []

    def received(data: bytes) -> None:
        with lock:
            window.append((time.monotonic(), len(data)))
            del window[: -args.window]

    node = ctx.client.node
    sub = node.create_subscription(
        msg_class, args.topic, received, qos_profile_sensor_data, raw=True
    )
    ctx.console.out(f"Subscribed to [{args.topic}]\n")
    try:
        while not ctx.console.cancelled.wait(1.0):
            with lock:
                sample = list(window)
            if len(sample) >= 2:
                ctx.console.out(bw_line([s for _t, s in sample], time.monotonic() - sample[0][0]))
    finally:
        node.destroy_subscription(sub)
    return 2


def _stamp_ns(msg: Any) -> int:
    if not hasattr(msg, "header"):
        raise RuntimeError("msg does not have header")  # ros2topic's words, on a message
    return msg.header.stamp.sec * 1_000_000_000 + msg.header.stamp.nanosec


def delay_arguments(parser: Parser) -> None:
    """Arguments of `ros2 topic delay`."""
    parser.add_argument("topic", help="Topic name to calculate the delay for")
    parser.add_argument(
        "--window",
        "-w",
        type=options.positive_int,
        default=10000,
        help="window size, in # of messages, for calculating rate, string to (default: 10000)",
    )
    options.direct(parser)


@verb(
    "topic", "delay", "Display delay of topic from timestamp in header", arguments=delay_arguments
)
def delay(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 topic delay <topic> [-w N]`: how old header stamps are on arrival, each second
    from the subscription on until Ctrl-C (a type without header: an error at its first
    message, as ros2topic's callback raises it)."""
    if args.use_sim_time:
        return "`ros2 topic delay --use-sim-time` is not part of this course: it uses wall time."
    from rclpy.qos import qos_profile_sensor_data

    from ..delay_window import DelayWindow
    from ..verbkit.topic_types import import_message

    type_name = _wait_for_type(ctx, args.topic)
    if type_name is None:
        return 2
    inbox: queue.Queue[tuple[int, Any]] = queue.Queue()
    node, window = ctx.client.node, DelayWindow(args.window)
    sub = node.create_subscription(
        import_message(type_name),
        args.topic,
        lambda msg: inbox.put((time.time_ns(), msg)),
        qos_profile_sensor_data,
    )
    tick = time.monotonic() + 1.0
    try:
        while not ctx.console.cancelled.wait(max(0.0, min(_POLL_S, tick - time.monotonic()))):
            while not inbox.empty():
                received, msg = inbox.get()
                window.add(received, _stamp_ns(msg))
            if time.monotonic() >= tick:
                tick += 1.0
                ctx.console.out(window.report() or "")
    finally:
        node.destroy_subscription(sub)
    return 2


def topic_command_arguments(parser: Parser) -> None:
    """The option `ros2 topic` itself takes before its verb."""
    parser.add_argument(
        "--include-hidden-topics", action="store_true", help="Consider hidden topics as well"
    )


command("topic", "Various topic related sub-commands", options=topic_command_arguments)


def topic_list_arguments(parser: Parser) -> None:
    """Arguments of `ros2 topic list`."""
    options.strategy(parser)
    parser.add_argument(
        "-t", "--show-types", action="store_true", help="Additionally show the topic type"
    )
    parser.add_argument(
        "-c",
        "--count-topics",
        action="store_true",
        help="Only display the number of topics discovered",
    )
    parser.add_argument(
        "--include-hidden-topics", action="store_true", help="Consider hidden topics as well"
    )
    parser.add_argument(
        "-v", "--verbose", action="store_true", help="List full details about each topic"
    )


@verb("topic", "list", "Output a list of available topics", arguments=topic_list_arguments)
def topic_list(args: argparse.Namespace, ctx: Context) -> int:
    """`ros2 topic list [-t] [-c] [-v]`."""
    client = settled_client(args, ctx)
    topics = client.topics(include_hidden=args.include_hidden_topics)
    if args.count_topics:
        return ctx.console.emit(render.topic_list(topics, count_only=True))
    if not topics:
        return 0
    if args.verbose:
        node = client.node
        for publishers in (True, False):
            lines = ["Published topics:" if publishers else "Subscribed topics:"]
            for topic in topics:
                n = (node.count_publishers if publishers else node.count_subscribers)(topic.name)
                if n:
                    kind = "publisher" if publishers else "subscriber"
                    lines.append(
                        f" * {topic.name} [{', '.join(topic.types)}] {n} {kind}"
                        + ("s" if n > 1 else "")
                    )
            ctx.console.out("\n".join(lines) + "\n\n")
        return 0
    return ctx.console.emit(render.topic_list(topics, show_types=args.show_types))
