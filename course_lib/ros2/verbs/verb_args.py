"""The arguments of each verb, in ros2cli 0.32.2's order with its help texts (pure)."""

from __future__ import annotations

import argparse

from ..node.discovery import DEFAULT_SPIN_TIME

__all__ = [
    "daemon_start",
    "node_info",
    "node_list",
    "param_delete",
    "param_describe",
    "param_dump",
    "param_get",
    "param_list",
    "param_load",
    "param_set",
    "pkg_executables",
    "pkg_prefix",
    "run",
    "topic_command",
    "topic_echo",
    "topic_hz",
    "topic_list",
]

Parser = argparse.ArgumentParser
_TIMEOUT_HELP = "Wait for N seconds until node becomes available (default %(default)s sec)"
_QOS = {
    "profile": [
        "unknown",
        "default",
        "system_default",
        "sensor_data",
        "services_default",
        "parameters",
        "parameter_events",
        "action_status_default",
        "best_available",
    ],
    "history": ["system_default", "keep_last", "keep_all", "unknown"],
    "reliability": ["system_default", "reliable", "best_effort", "unknown", "best_available"],
    "durability": ["system_default", "transient_local", "volatile", "unknown", "best_available"],
    "liveliness": ["system_default", "automatic", "manual_by_topic", "unknown", "best_available"],
}


def _direct(parser: Parser) -> None:
    parser.add_argument(
        "--spin-time",
        type=float,
        default=DEFAULT_SPIN_TIME,
        help="Spin time in seconds to wait for discovery (only applies when not using an "
        "already running daemon)",
    )
    parser.add_argument(
        "-s", "--use-sim-time", action="store_true", help="Enable ROS simulation time"
    )


def _strategy(parser: Parser) -> None:
    _direct(parser)
    parser.add_argument(
        "--no-daemon", action="store_true", help="Do not spawn nor use an already running daemon"
    )


def _node_and_hidden(parser: Parser) -> None:
    _strategy(parser)
    parser.add_argument("node_name", help="Name of the ROS node")
    parser.add_argument(
        "--include-hidden-nodes", action="store_true", help="Consider hidden nodes as well"
    )


def _timeout(parser: Parser) -> None:
    parser.add_argument("--timeout", metavar="N", type=int, default=1, help=_TIMEOUT_HELP)


def daemon_start(parser: Parser) -> None:
    """Arguments of `ros2 daemon start`."""
    parser.add_argument("--debug", "-d", action="store_true", help="Print debug messages")


def node_list(parser: Parser) -> None:
    """Arguments of `ros2 node list`."""
    _strategy(parser)
    parser.add_argument(
        "-a", "--all", action="store_true", help="Display all nodes even hidden ones"
    )
    parser.add_argument(
        "-c",
        "--count-nodes",
        action="store_true",
        help="Only display the number of nodes discovered",
    )


def node_info(parser: Parser) -> None:
    """Arguments of `ros2 node info`."""
    _strategy(parser)
    parser.add_argument("node_name", help="Node name to request information")
    parser.add_argument(
        "--include-hidden",
        action="store_true",
        help="Display hidden topics, services, and actions as well",
    )


def param_list(parser: Parser) -> None:
    """Arguments of `ros2 param list`."""
    _strategy(parser)
    parser.add_argument("node_name", nargs="?", help="Name of the ROS node")
    parser.add_argument(
        "--filter",
        nargs=1,
        help="Only parameters matching the regex expression will be showed. Supports `re` "
        "regex syntax.",
    )
    parser.add_argument(
        "--include-hidden-nodes", action="store_true", help="Consider hidden nodes as well"
    )
    parser.add_argument(
        "--param-prefixes",
        nargs="+",
        default=[],
        help="Only list parameters with the provided prefixes",
    )
    parser.add_argument(
        "--param-type", action="store_true", help="Print parameter types with parameter names"
    )


def param_get(parser: Parser) -> None:
    """Arguments of `ros2 param get`."""
    _node_and_hidden(parser)
    parser.add_argument("parameter_name", help="Name of the parameter")
    parser.add_argument("--hide-type", action="store_true", help="Hide the type information")
    _timeout(parser)


def param_set(parser: Parser) -> None:
    """Arguments of `ros2 param set`."""
    _node_and_hidden(parser)
    parser.add_argument("parameter_name", help="Name of the parameter")
    parser.add_argument("value", help="Value of the parameter")
    _timeout(parser)


def param_describe(parser: Parser) -> None:
    """Arguments of `ros2 param describe`."""
    _node_and_hidden(parser)
    parser.add_argument("parameter_names", nargs="+", help="Names of the parameters")
    _timeout(parser)


def param_dump(parser: Parser) -> None:
    """Arguments of `ros2 param dump`."""
    _node_and_hidden(parser)
    _timeout(parser)


def param_load(parser: Parser) -> None:
    """Arguments of `ros2 param load`."""
    _node_and_hidden(parser)
    parser.add_argument("parameter_file", help="Parameter file")
    parser.add_argument(
        "--no-use-wildcard",
        action="store_true",
        help="Do not load parameters in the '/**' namespace into the node",
    )
    _timeout(parser)


def param_delete(parser: Parser) -> None:
    """Arguments of `ros2 param delete`."""
    _node_and_hidden(parser)
    parser.add_argument("parameter_name", help="Name of the parameter")
    _timeout(parser)


def topic_command(parser: Parser) -> None:
    """The option `ros2 topic` itself takes before its verb."""
    parser.add_argument(
        "--include-hidden-topics", action="store_true", help="Consider hidden topics as well"
    )


def topic_list(parser: Parser) -> None:
    """Arguments of `ros2 topic list`."""
    _strategy(parser)
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


def _unsigned_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError("value must be non-negative integer")
    return value


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("Expects a floating point number") from None
    if value <= 0.0:
        raise argparse.ArgumentTypeError("Value must be positive")
    return value


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value <= 0:
        raise argparse.ArgumentTypeError("value must be a positive integer")
    return value


def _qos(parser: Parser, verb: str = "subscribe", default: str = "sensor_data") -> None:
    parser.add_argument(
        "--qos-profile",
        choices=_QOS["profile"],
        default=default,
        help=f"Quality of service preset profile to {verb} with (default: {default})",
    )
    parser.add_argument(
        "--qos-depth",
        metavar="N",
        type=int,
        help=f"Queue size setting to {verb} with (overrides depth value of --qos-profile option)",
    )
    parser.add_argument(
        "--qos-history",
        choices=_QOS["history"],
        help=f"History of samples setting to {verb} with (overrides history value of "
        "--qos-profile option, default: keep_last)",
    )
    for policy in ("reliability", "durability"):
        parser.add_argument(
            f"--qos-{policy}",
            choices=_QOS[policy],
            help=f"Quality of service {policy} setting to {verb} with (overrides {policy} value "
            "of --qos-profile option, default: Compatible profile with running endpoints )",
        )
    parser.add_argument(
        "--qos-liveliness",
        choices=_QOS["liveliness"],
        help=f"Quality of service liveliness setting to {verb} with (overrides liveliness value "
        "of --qos-profile option",
    )
    parser.add_argument(
        "--qos-liveliness-lease-duration-seconds",
        type=float,
        help=f"Quality of service liveliness lease duration setting to {verb} with (overrides "
        "liveliness lease duration value of --qos-profile option",
    )


def topic_echo(parser: Parser) -> None:
    """Arguments of `ros2 topic echo`."""
    _strategy(parser)
    parser.add_argument("topic_name", help="Name of the ROS topic to listen to (e.g. '/chatter')")
    parser.add_argument(
        "message_type", nargs="?", help="Type of the ROS message (e.g. 'std_msgs/msg/String')"
    )
    _qos(parser)
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
        type=_unsigned_int,
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
        type=_positive_float,
        help="Set a timeout in seconds for waiting",
        default=None,
    )
    parser.add_argument(
        "--include-message-info",
        "-i",
        action="store_true",
        help="Shows the associated message info.",
    )


def topic_hz(parser: Parser) -> None:
    """Arguments of `ros2 topic hz`."""
    parser.add_argument("topic_name", help="Name of the ROS topic to listen to (e.g. '/chatter')")
    parser.add_argument(
        "--window",
        "-w",
        dest="window_size",
        type=_positive_int,
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
    _direct(parser)


def pkg_executables(parser: Parser) -> None:
    """Arguments of `ros2 pkg executables`."""
    parser.add_argument("package_name", nargs="?", help="The package name")
    parser.add_argument(
        "--full-path", action="store_true", default=False, help="Show full path of each executable"
    )


def pkg_prefix(parser: Parser) -> None:
    """Arguments of `ros2 pkg prefix`."""
    parser.add_argument("package_name", help="The package name")
    parser.add_argument(
        "--share", action="store_true", help="Show share directory for the package"
    )


def run(parser: Parser) -> None:
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


def strategy(parser: Parser) -> None:
    """Add ros2cli's node-strategy options (`--spin-time`, `-s`, `--no-daemon`)."""
    _strategy(parser)


def qos(parser: Parser, verb: str, default: str) -> None:
    """Add ros2topic's QoS options (`--qos-profile`, `--qos-depth`, ...)."""
    _qos(parser, verb, default)


def direct(parser: Parser) -> None:
    """Add ros2cli's direct-node options (`--spin-time`, `-s`)."""
    _direct(parser)


positive_float = _positive_float
positive_int = _positive_int
