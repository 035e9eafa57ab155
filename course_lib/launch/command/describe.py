"""`ros2 launch --show-args`: the launch file's arguments, as ros2launch prints them."""

from __future__ import annotations

import sys

from ..core.loading import load_any_launch_file
from ..runtime.shim import launch_modules

__all__ = ["format_arguments", "print_arguments_of_launch_file"]


def format_arguments(description: object) -> str:
    """Return the `--show-args` text for a launch description."""
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    arguments = description.get_launch_arguments()  # type: ignore[attr-defined]
    conditional = False
    for argument in arguments:
        text = f"\n    '{argument.name}':"
        if argument._conditionally_included:
            conditional = True
            text += "*"
        text += f"\n        {argument.description}"
        if argument.default_value is not None:
            default = " + ".join(token.describe() for token in argument.default_value)
            text += f"\n        (default: {default})"
        lines.append(text)
    if arguments:
        if conditional:
            lines.append("\n* argument(s) which are only used if specific conditions occur")
    else:
        lines.append("\n  No arguments.")
    return "\n".join(lines) + "\n"


def print_arguments_of_launch_file(path: str) -> int:
    """Print the arguments of the launch file at `path`; return the exit code."""
    try:
        with launch_modules():
            description = load_any_launch_file(path)
            text = format_arguments(description)
    except Exception as exc:
        print(str(exc), file=sys.stderr)
        return 1
    print(text, end="")
    return 0
