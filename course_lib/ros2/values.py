"""Parameter values and their ROS types, parsed from text exactly as ros2cli parses them (pure)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import yaml

__all__ = [
    "NOT_SET",
    "TYPE_NAMES",
    "ParamValue",
    "parse_value",
    "type_name",
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
            return _array_of(list(value), str(value), strict=True)
        raise TypeError(f"no ROS parameter type holds {value!r}")


def _array_of(items: list[Any], text: str, *, strict: bool = False) -> ParamValue:
    for kind, array in ((bool, BOOL_ARRAY), (int, INTEGER_ARRAY), (float, DOUBLE_ARRAY)):
        if all(isinstance(v, kind) for v in items):
            return ParamValue(array, tuple(items))
    if all(isinstance(v, str) for v in items):
        return ParamValue(STRING_ARRAY, tuple(items))
    if strict:
        raise TypeError(f"a ROS array parameter holds one type only, not {items!r}")
    return ParamValue(STRING, text)


def parse_value(text: str) -> ParamValue:
    """Guess a value's type from text with YAML rules, as `ros2 param set` does (no conversion).

    `0.2` is a double, `1` an integer, `true` a boolean, `abc` a string and
    `[1.0, 2.0]` a double array; a list mixing types stays the original string.
    """
    try:
        parsed = yaml.safe_load(text)
    except yaml.parser.ParserError:
        parsed = text
    if isinstance(parsed, bool):
        return ParamValue(BOOL, parsed)
    if isinstance(parsed, int):
        return ParamValue(INTEGER, parsed)
    if isinstance(parsed, float):
        return ParamValue(DOUBLE, parsed)
    if isinstance(parsed, list):
        return _array_of(parsed, text)
    if parsed is None:
        return ParamValue(STRING, text)
    if not isinstance(parsed, str):
        # ros2cli crashes here (a mapping is no parameter value); keep its error's words.
        raise AssertionError("The 'string_value' field must be of type 'str'")
    return ParamValue(STRING, parsed)
