"""Parameter values and their ROS types; text is parsed by rclpy's own guess, as ros2cli does.

Pure but for `parse_value`, which imports rclpy when called (in the process holding a node).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = [
    "NOT_SET",
    "TYPE_NAMES",
    "VALUE_FIELDS",
    "ParamValue",
    "event_record",
    "from_journal",
    "journal_value",
    "parse_value",
    "type_name",
    "value_from_msg",
]

# rcl_interfaces/msg/ParameterType constants.
NOT_SET, BOOL, INTEGER, DOUBLE, STRING = 0, 1, 2, 3, 4
BYTE_ARRAY, BOOL_ARRAY, INTEGER_ARRAY, DOUBLE_ARRAY, STRING_ARRAY = 5, 6, 7, 8, 9

TYPE_NAMES = {
    BOOL: "boolean",
    INTEGER: "integer",
    DOUBLE: "double",
    STRING: "string",
    BYTE_ARRAY: "byte array",
    BOOL_ARRAY: "boolean array",
    INTEGER_ARRAY: "integer array",
    DOUBLE_ARRAY: "double array",
    STRING_ARRAY: "string array",
    NOT_SET: "not set",
}

# The labels `ros2 param get` prints before a value.
GET_LABELS = {
    BOOL: "Boolean value is:",
    INTEGER: "Integer value is:",
    DOUBLE: "Double value is:",
    STRING: "String value is:",
    BYTE_ARRAY: "Byte values are:",
    BOOL_ARRAY: "Boolean values are:",
    INTEGER_ARRAY: "Integer values are:",
    DOUBLE_ARRAY: "Double values are:",
    STRING_ARRAY: "String values are:",
}

ARRAY_TYPES = (BYTE_ARRAY, BOOL_ARRAY, INTEGER_ARRAY, DOUBLE_ARRAY, STRING_ARRAY)

# The field of an rcl_interfaces ParameterValue message that holds each type's value.
VALUE_FIELDS = {
    BOOL: "bool_value",
    INTEGER: "integer_value",
    DOUBLE: "double_value",
    STRING: "string_value",
    BYTE_ARRAY: "byte_array_value",
    BOOL_ARRAY: "bool_array_value",
    INTEGER_ARRAY: "integer_array_value",
    DOUBLE_ARRAY: "double_array_value",
    STRING_ARRAY: "string_array_value",
}


def type_name(ros_type: int) -> str:
    """Return the word ros2cli uses for a ParameterType constant (`double`, ...)."""
    return TYPE_NAMES[ros_type]


@dataclass(frozen=True)
class ParamValue:
    """A parameter value with its ROS type; arrays are tuples."""

    type: int
    value: Any = None

    @property
    def type_name(self) -> str:
        """Return the ROS type's word, as `ros2 param list --param-type` shows it."""
        return TYPE_NAMES[self.type]

    @property
    def python(self) -> Any:
        """Return the value as plain Python (arrays as lists, NOT_SET as None)."""
        return list(self.value) if self.type in ARRAY_TYPES else self.value

    @classmethod
    def of(cls, value: Any) -> ParamValue:
        """Return the ParamValue of a Python value (bool, int, float, str or a list of one)."""
        if isinstance(value, ParamValue):
            return value
        if value is None:
            return cls(NOT_SET)
        for kind, array in ((bool, BOOL), (int, INTEGER), (float, DOUBLE), (str, STRING)):
            if isinstance(value, kind):
                return cls(array, value)
        if isinstance(value, (bytes, bytearray)):
            return cls(BYTE_ARRAY, tuple(bytes([b]) for b in value))
        if isinstance(value, (list, tuple)):
            return _array_of(list(value))
        raise TypeError(f"no ROS parameter type holds {value!r}")


def _array_of(items: list[Any]) -> ParamValue:
    for kind, array in (
        (bool, BOOL_ARRAY),
        (int, INTEGER_ARRAY),
        (float, DOUBLE_ARRAY),
        (str, STRING_ARRAY),
    ):
        if all(isinstance(v, kind) for v in items):
            return ParamValue(array, tuple(items))
    raise TypeError(f"a ROS array parameter holds one type only, not {items!r}")


def parse_value(text: str) -> ParamValue:
    """Guess a value's type from text as `ros2 param set` does: with rclpy's own guess.

    YAML rules, no conversion: `0.2` is a double, `1` an integer, `true` a boolean, `abc` a
    string and `[1.0, 2.0]` a double array; a list mixing types stays the original string.
    A mapping (or a date) is no parameter value: it raises the AssertionError rclpy's
    message raises when its field checks are on (ROS_PYTHON_CHECK_FIELDS), never reaching
    the node.
    """
    # rclpy only here: values are parsed in the process that holds the node, never to render.
    from rclpy.parameter import get_parameter_value

    value = value_from_msg(get_parameter_value(text))
    if value.type == STRING and not isinstance(value.value, str):
        raise AssertionError("The 'string_value' field must be of type 'str'")
    return value


def value_from_msg(msg: Any) -> ParamValue:
    """Convert an rcl_interfaces ParameterValue into a ParamValue (arrays as tuples)."""
    field = VALUE_FIELDS.get(msg.type)
    if field is None:
        return ParamValue(msg.type)
    raw = getattr(msg, field)
    if msg.type in ARRAY_TYPES:
        raw = tuple(raw.tolist() if hasattr(raw, "tolist") else raw)
    return ParamValue(msg.type, raw)


def journal_value(value: ParamValue) -> list[Any]:
    """Return a value as the parameter journal stores it: `[type, plain JSON value]`."""
    raw = value.python
    if value.type == BYTE_ARRAY:
        raw = [b[0] if isinstance(b, bytes) else int(b) for b in raw]
    return [value.type, raw]


def from_journal(stored: Any) -> ParamValue | None:
    """Return the ParamValue of a journal's `[type, value]` (None for anything else)."""
    if not isinstance(stored, list) or len(stored) != 2 or stored[0] not in TYPE_NAMES:
        return None
    kind, raw = stored
    if kind == BYTE_ARRAY:
        return ParamValue(kind, tuple(bytes([b]) for b in raw))
    return ParamValue(kind, tuple(raw) if kind in ARRAY_TYPES else raw)


def event_record(msg: Any, sim: float | None = None) -> dict[str, Any] | None:
    """Return the parameter journal's record of a /parameter_events message (`sim`: the
    simulated time it was heard at, if known), or None for the course's and ros2cli's own
    hidden nodes."""
    if msg.node.startswith("/_"):
        return None
    changes = [
        {"kind": kind, "name": p.name, "value": journal_value(value_from_msg(p.value))}
        for kind, params in (
            ("new", msg.new_parameters),
            ("changed", msg.changed_parameters),
            ("deleted", msg.deleted_parameters),
        )
        for p in params
    ]
    stamp = msg.stamp.sec + msg.stamp.nanosec * 1e-9
    return {"t": "event", "node": msg.node, "stamp": stamp, "sim": sim, "changes": changes}
