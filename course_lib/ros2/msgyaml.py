"""Render ROS messages as `ros2 topic echo` does (YAML in field order), by duck typing (pure)."""

from __future__ import annotations

import array
import sys
from collections import OrderedDict
from typing import Any

import yaml

__all__ = ["array_info", "message_to_ordereddict", "message_to_yaml"]


class _Dumper(yaml.Dumper):
    """A dumper that keeps field order, as rosidl_runtime_py's representer does."""


def _represent_ordered(dumper: yaml.Dumper, data: OrderedDict) -> yaml.Node:
    items = [(dumper.represent_data(k), dumper.represent_data(v)) for k, v in data.items()]
    return yaml.nodes.MappingNode("tag:yaml.org,2002:map", items)


_Dumper.add_representer(OrderedDict, _represent_ordered)


def _is_message(value: Any) -> bool:
    return hasattr(value, "get_fields_and_field_types")


def array_info(value: Any, field_type: Any) -> str:
    """Return `--no-arr`'s stand-in for an array or sequence field (its type and length)."""
    kind = type(field_type).__name__
    inner = getattr(field_type, "value_type", None)
    name = getattr(inner, "typename", None) or getattr(inner, "name", None) or "unknown"
    if inner is not None and hasattr(inner, "namespaced_name"):
        name = "/".join(inner.namespaced_name())
    elif type(inner).__name__ in ("UnboundedString", "BoundedString"):
        name = "string"
    if kind == "Array":
        return f"<array type: {name}[{field_type.size}]>"
    if kind == "BoundedSequence":
        return f"<sequence type: {name}[{field_type.maximum_size}], length: {len(value)}>"
    if kind == "UnboundedSequence":
        return f"<sequence type: {name}, length: {len(value)}>"
    return "unknown"


def _convert(value: Any, field_type: Any, limit: int | None, no_arr: bool, no_str: bool) -> Any:
    if isinstance(value, bytes):
        if limit is not None and len(value) > limit:
            return "".join(chr(c) for c in value[:limit]) + "..."
        return "".join(chr(c) for c in value)
    if isinstance(value, str):
        if no_str:
            return f"<string length: <{len(value)}>>"
        return value[:limit] + "..." if limit is not None and len(value) > limit else value
    if isinstance(value, (list, tuple, array.array)) or type(value).__name__ == "ndarray":
        if no_arr and field_type is not None:
            return array_info(value, field_type)
        items = list(value)
        cut = limit is not None and len(items) > limit
        items = [_convert(v, None, limit, no_arr, no_str) for v in items[: limit if cut else None]]
        if cut:
            items.append("...")
        return tuple(items) if isinstance(value, tuple) else items
    if hasattr(value, "item") and not isinstance(value, (bool, int, float)):
        return value.item()
    if _is_message(value):
        return message_to_ordereddict(value, truncate_length=limit, no_arr=no_arr, no_str=no_str)
    return value


def message_to_ordereddict(
    msg: Any, *, truncate_length: int | None = None, no_arr: bool = False, no_str: bool = False
) -> OrderedDict:
    """Return the message's fields in .msg order, values converted for YAML."""
    fields = msg.get_fields_and_field_types().keys()
    slot_types = getattr(msg, "SLOT_TYPES", [None] * len(fields))
    return OrderedDict(
        (name, _convert(getattr(msg, name, None), ftype, truncate_length, no_arr, no_str))
        for name, ftype in zip(fields, slot_types, strict=False)
    )


def message_to_yaml(
    msg: Any,
    *,
    truncate_length: int | None = 128,
    no_arr: bool = False,
    no_str: bool = False,
    flow_style: bool = False,
) -> str:
    """Return the YAML text `ros2 topic echo` prints for one message (without `---`)."""
    return yaml.dump(
        message_to_ordereddict(msg, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str),
        Dumper=_Dumper,
        allow_unicode=True,
        width=sys.maxsize,
        default_flow_style=flow_style,
    )
