"""Options many verbs share, in ros2cli 0.32.2's words: node strategy, QoS, timeouts (pure).

Each verb's own arguments live in its verb module (`<verb>_arguments`), beside its handler.
"""

from __future__ import annotations

import argparse

from ..node.discovery import DEFAULT_SPIN_TIME

__all__ = [
    "direct",
    "node_and_hidden",
    "positive_float",
    "positive_int",
    "qos",
    "strategy",
    "timeout",
    "unsigned_int",
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


def node_and_hidden(parser: Parser) -> None:
    """Add the node-name argument and `--include-hidden-nodes` (param verbs)."""
    _node_and_hidden(parser)


def timeout(parser: Parser) -> None:
    """Add `--timeout N`: wait for the node that long (param verbs)."""
    _timeout(parser)


unsigned_int = _unsigned_int
