"""Render a ROS message as `ros2 topic echo --csv` does: one comma-separated line (pure).

rosidl_runtime_py's rules: fields in .msg order, nested messages flattened in place, every
element of an array or sequence its own value (an empty one adds an empty value, except at
the very start: a comma follows only what is not empty), each value
as Python's `str` (so bytes read `b'\\x02'`, nothing is quoted or escaped). Strings, bytes
and arrays longer than `truncate_length` are cut, an array's rest standing as one `...`.
Works on any rosidl-generated message by duck typing; no rclpy import.
"""

from __future__ import annotations

import array
from typing import Any

from .msgyaml import array_info

__all__ = ["message_to_csv"]


def _joined(parts: list[str]) -> str:
    """Join as rosidl_runtime_py does: a comma only after a non-empty start (an empty first
    value, such as an empty string, leaves no comma before the next)."""
    line = ""
    for part in parts:
        line = f"{line},{part}" if line else part
    return line


def _is_array(value: Any) -> bool:
    return isinstance(value, (list, tuple, array.array)) or type(value).__name__ == "ndarray"


def _is_number(value: Any) -> bool:
    """A numpy scalar (an element of a fixed-size numeric array) counts as a number."""
    return any(base.__name__ == "number" for base in type(value).__mro__)


def _value(value: Any, field_type: Any, limit: int | None, no_arr: bool, no_str: bool) -> str:
    if _is_array(value):
        if no_arr and field_type is not None:
            return array_info(value, field_type)
        items = []
        for index, item in enumerate(value):
            if limit is not None and index >= limit:
                items.append("...")
                break
            items.append(_value(item, None, limit, no_arr, no_str))
        return _joined(items)
    if isinstance(value, (bool, bytes, float, int, str)) or _is_number(value):
        if no_str and isinstance(value, str):
            value = f"<string length: <{len(value)}>>"
        elif isinstance(value, (bytes, str)) and limit is not None and len(value) > limit:
            value = value[:limit] + b"..." if isinstance(value, bytes) else value[:limit] + "..."
        return str(value)
    return message_to_csv(value, truncate_length=limit, no_arr=no_arr, no_str=no_str)


def message_to_csv(
    msg: Any, *, truncate_length: int | None = None, no_arr: bool = False, no_str: bool = False
) -> str:
    """Return the message's fields as one comma-separated line (without its newline)."""
    fields = msg.get_fields_and_field_types().keys()
    slot_types = getattr(msg, "SLOT_TYPES", [None] * len(fields))
    return _joined(
        [
            _value(getattr(msg, name), ftype, truncate_length, no_arr, no_str)
            for name, ftype in zip(fields, slot_types, strict=False)
        ]
    )
