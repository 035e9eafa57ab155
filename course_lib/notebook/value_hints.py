"""The pure hints of a mistyped `ros2` command: closest names, values split at their spaces or
followed by a unit, type mismatches, and a velocity the robot cannot reach (no ROS here)."""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable, Sequence

from ..config.trip import VELOCITY_MAX_MPS

__all__ = [
    "SET_SUCCESSFUL",
    "UNITS",
    "VEL_NODE",
    "WRONG_TYPE",
    "absolute",
    "closest",
    "joined_value",
    "missing_name_hint",
    "positionals",
    "split_hint",
    "top_speed_hint",
    "type_hint",
    "unit_hint",
]

WRONG_TYPE = re.compile(r"Wrong parameter type, expected 'Type\.(\w+)' got 'Type\.(\w+)'")
_VALUED_OPTIONS = {"--timeout", "--spin-time", "--filter", "--param-prefixes"}
_WORDS = {
    "DOUBLE": "a double (a number with a decimal point)",
    "INTEGER": "an integer",
    "BOOL": "a bool",
    "STRING": "a string",
    "BYTE_ARRAY": "a byte array",
    "BOOL_ARRAY": "an array of bools",
    "INTEGER_ARRAY": "an array of integers",
    "DOUBLE_ARRAY": "an array of doubles",
    "STRING_ARRAY": "an array of strings",
}
_EXAMPLES = {
    "DOUBLE": "0.2",
    "INTEGER": "3",
    "BOOL": "true",
    "STRING": "hello",
    "BOOL_ARRAY": "'[true, false]'",
    "INTEGER_ARRAY": "'[1, 2]'",
    "DOUBLE_ARRAY": "'[1.0, 2.0]'",
    "STRING_ARRAY": "'[a, b]'",
}

# the course's parameters with a unit: what a learner may type after the number
UNITS = {"velocity": "m/s", "travel_time": "s", "max_travel": "m"}
_UNIT_WORDS = frozenset(
    {"m/s", "mps", "m/sec", "km/h", "m", "cm", "mm", "meter", "meters", "metre", "metres"}
    | {"s", "sec", "secs", "second", "seconds", "ms", "min", "hz"}
    | {"rad/s", "rad", "deg", "deg/s", "degrees"}
)
_NUMBER = re.compile(r"[-+]?(?:\d+(?:[.,]\d*)?|[.,]\d+)(?:[eE][-+]?\d+)?")
SET_SUCCESSFUL = "Set parameter successful"
VEL_NODE = "/param_vel_node"  # the tutorial node: its velocity has no range, the robot has


# --- pure: names ----------------------------------------------------------------------------
def closest(name: str, known: Iterable[str]) -> str | None:
    """Return the known name most like `name` (difflib, ratio >= 0.6), or None."""
    candidates = sorted(set(known) - {name})
    match = difflib.get_close_matches(name, candidates, n=1, cutoff=0.6)
    return match[0] if match else None


def missing_name_hint(what: str, name: str, known: Sequence[str], show: str) -> str:
    """Say that `name` does not exist and which existing one it is most like."""
    near = closest(name, known)
    if near is not None:
        return f"there is no {what} '{name}'; did you mean '{near}'? ({show} lists them)"
    if not known and what == "node":
        return f"no node is running, so there is no '{name}': start the node first."
    return f"there is no {what} '{name}' and none with a close name; {show} lists them."


# --- pure: the command line -----------------------------------------------------------------
def positionals(argv: Sequence[str]) -> list[str]:
    """Return the arguments of a `ros2` command line that are not options or their values."""
    found: list[str] = []
    skip = False
    for token in argv:
        if skip:
            skip = False
            continue
        if token in _VALUED_OPTIONS:
            skip = True
            continue
        if token.startswith("-") and not re.match(r"-[\d.]", token):
            continue
        found.append(token)
    return found


def joined_value(argv: Sequence[str]) -> str | None:
    """Return the value of `param set NODE NAME VALUE...` when it was split into several
    arguments at its spaces (by the shell or the magic), joined again; else None."""
    words = positionals(argv)
    if words[:2] != ["param", "set"] or len(words) <= 5:
        return None
    return " ".join(words[4:])


def _number_in(text: str) -> str | None:
    """Return the first number written in `text` (`0.15 m/s` -> `0.15`), or None."""
    found = _NUMBER.search(text)
    return found.group(0).replace(",", ".") if found else None


def _format_double(text: str) -> str:
    """Return the double a learner meant by `text` (`1` -> `1.0`, `0,5` -> `0.5`,
    `0.15 m/s` -> `0.15`)."""
    number = _number_in(text.strip().strip("'\""))
    try:
        return repr(float(number)) if number is not None else _EXAMPLES["DOUBLE"]
    except ValueError:
        return _EXAMPLES["DOUBLE"]


def _no_unit(name: str) -> str:
    """Return the words that say a parameter carries no unit (and the one it is in)."""
    unit = UNITS.get(name)
    return "parameters carry no unit" + (f"; {name} is in {unit}" if unit else "")


def _text_for_number(name: str, kind: str, value: str, meant: str) -> str:
    """Say that `value` was read as text and how to write the number it holds."""
    number = _number_in(value) or ""
    rest = value.replace(number.replace(".", ","), "").replace(number, "")
    unit = f" ({_no_unit(name)})" if number and re.search(r"[a-zA-Z]", rest) else ""
    return (
        f"'{name}' is {kind}; `{value}` was read as text and ROS does not convert it: "
        f"write `{meant}`{unit}."
    )


def type_hint(reason: str, name: str, value: str) -> str | None:
    """Return the hint for Jazzy's `Wrong parameter type` reason, or None for another one."""
    match = WRONG_TYPE.search(reason)
    if match is None:
        return None
    expected, got = match.groups()
    kind = _WORDS.get(expected, expected.lower())
    if expected == "DOUBLE" and got == "INTEGER":
        return (
            f"'{name}' is {kind}; `{value}` was read as an integer and ROS does not convert "
            f"it: write `{_format_double(value)}`."
        )
    if expected == "DOUBLE" and got == "STRING":
        return _text_for_number(name, kind, value, _format_double(value))
    number = _number_in(value)
    if expected == "INTEGER" and got == "STRING" and number is not None:
        return _text_for_number(name, kind, value, str(int(float(number))))
    if expected == "INTEGER" and got == "DOUBLE":
        return f"'{name}' is {kind}; write it without a decimal point, e.g. `{int(float(value))}`."
    if expected.endswith("_ARRAY"):
        return (
            f"'{name}' is {kind}: write it in brackets and in quotes, as one argument, "
            f"e.g. {_EXAMPLES.get(expected, _EXAMPLES['DOUBLE_ARRAY'])}."
        )
    if expected == "STRING":
        return (
            f"'{name}' is {kind}; `{value}` was read as a number or bool: quote it, '\"{value}\"'."
        )
    return f"'{name}' is {kind}; write a value of that type, e.g. `{_EXAMPLES.get(expected, '')}`."


def unit_hint(words: Sequence[str]) -> str | None:
    """Return the hint for `param set NODE NAME NUMBER UNIT` (a unit after the number, split
    off at its space), or None for another split value."""
    if words[:2] != ["param", "set"] or len(words) < 6:
        return None
    number, rest = words[4], [w.lower() for w in words[5:]]
    if _number_in(number) != number.replace(",", ".") or not set(rest) <= _UNIT_WORDS:
        return None
    node, name = absolute(words[2]), words[3]
    typed = _format_double(number) if name in UNITS else number
    top = (
        f"; the robot tops out at {VELOCITY_MAX_MPS:g} m/s"
        if node == VEL_NODE and name == "velocity" and abs(float(typed)) > VELOCITY_MAX_MPS
        else ""
    )
    unit = f" ({name} is in {UNITS[name]}{top})" if name in UNITS else ""
    return f"parameters carry no unit: `%ros2 param set {node} {name} {typed}`{unit}."


def top_speed_hint(words: Sequence[str], stdout: str) -> str | None:
    """Return the hint for a velocity the robot cannot reach that /param_vel_node accepted
    (the tutorial's node declares no range), or None."""
    if words[:2] != ["param", "set"] or len(words) < 5 or not stdout.startswith(SET_SUCCESSFUL):
        return None
    if absolute(words[2]) != VEL_NODE or words[3] != "velocity":
        return None
    try:
        value = float(words[4])
    except ValueError:
        return None
    if abs(value) <= VELOCITY_MAX_MPS:
        return None
    way = "forwards" if value > 0 else "backwards"
    return (
        f"{VEL_NODE} now holds velocity {words[4]} (its velocity has no range), but the robot "
        f"tops out at {VELOCITY_MAX_MPS:g} m/s: it drives {way} at {VELOCITY_MAX_MPS:g} m/s."
    )


def split_hint(value: str) -> str:
    """Return the hint for a value the shell or the magic split at its spaces."""
    count = len(value.split())
    return (
        f"the value `{value}` was split at its spaces into {count} arguments: "
        f"put it in quotes, as one argument: '{value}'."
    )


def absolute(name: str) -> str:
    """Return a node's name with its leading slash (`param_vel_node` -> `/param_vel_node`)."""
    return name if name.startswith("/") else "/" + name
