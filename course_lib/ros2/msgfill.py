"""Fill a ROS message from YAML values as ros2cli does (`service call`, `topic pub`).

Same rules as rosidl_runtime_py's set_message_fields: a value is converted with the field's
own Python type (so a string given for a `string[]` field becomes a list of characters, as
in Jazzy), nested messages and sequences of messages are filled recursively. Works on any
rosidl-generated message by duck typing; no rclpy import.
"""

from __future__ import annotations

import array
import importlib
from collections.abc import Callable
from functools import partial
from typing import Any

__all__ = ["import_type", "set_message_fields"]

_HEADER = "std_msgs.msg._header.Header"
_TIME = "builtin_interfaces.msg._time.Time"


def import_type(name: str, kind: str) -> Any:
    """Import `pkg/kind/Name` (or `pkg/Name`); raise ValueError/ImportError/AttributeError."""
    parts = name.split("/")
    if len(parts) == 2:
        parts = [parts[0], kind, parts[1]]
    module = importlib.import_module(".".join(parts[:-1]))
    return getattr(module, parts[-1])


def _slot_types(msg: Any) -> dict[str, Any]:
    return dict(zip(msg.get_fields_and_field_types(), msg.SLOT_TYPES, strict=False))


def _nested_class(slot: Any) -> Any | None:
    """Return the message class of a sequence/array of messages, else None."""
    value_type = getattr(slot, "value_type", None)
    if value_type is None or type(value_type).__name__ != "NamespacedType":
        return None
    module = importlib.import_module(".".join(value_type.namespaces))
    return getattr(module, value_type.name)


def _convert(field: Any, value: Any, stamps: list[Callable[..., Any]], fill: Callable) -> Any:
    field_type = type(field)
    if field_type is array.array:
        return array.array(field.typecode, value)
    if field_type.__name__ == "ndarray":
        import numpy

        return numpy.array(value, dtype=field.dtype)
    if type(value) is field_type:
        return value
    try:
        return field_type(value)
    except TypeError:
        nested = field_type()
        fill(nested, value)
        return nested


def set_message_fields(
    msg: Any, values: Any, *, expand_header_auto: bool = False, expand_time_now: bool = False
) -> list[Callable[..., Any]]:
    """Set msg's fields from a YAML mapping; return setters for `auto`/`now` stamps."""
    stamps: list[Callable[..., Any]] = []

    def fill(target: Any, mapping: Any) -> None:
        try:
            items = mapping.items()
        except AttributeError:
            raise TypeError(
                f"Value '{mapping}' is expected to be a dictionary but is a "
                f"{type(mapping).__name__}"
            ) from None
        for name, value in items:
            field = getattr(target, name)
            qualified = f"{type(field).__module__}.{type(field).__name__}"
            if qualified == _HEADER and value == "auto" and expand_header_auto:
                stamps.append(partial(setattr, field, "stamp"))
                continue
            if qualified == _TIME and value == "now" and expand_time_now:
                stamps.append(partial(setattr, target, name))
                continue
            converted = _convert(field, value, stamps, fill)
            element = _nested_class(_slot_types(target)[name])
            if element is not None:
                for i, item in enumerate(converted):
                    sub = element()
                    fill(sub, item)
                    converted[i] = sub
            setattr(target, name, converted)

    fill(msg, values)
    return stamps
