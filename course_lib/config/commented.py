"""Write an instructor file's comments from its schema: meaning, allowed range, default (pure).

The comments next to every key of config/*.yaml and the table of settings in
book/guides/instructor-settings.md come from the same `setting(help=..., ge=..., ...)`
declarations the validator checks, so they cannot drift apart: `make check-config
ARGS=--write-comments` rewrites the files' comments keeping their values, and a test checks
that the shipped files are exactly what this module writes.
"""

from __future__ import annotations

import dataclasses
import textwrap
import typing
from typing import Any, Literal

from .loader import describe_limits

__all__ = ["commented_yaml", "settings_rows"]

_WIDTH = 95


def _scalar(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, tuple):
        return "[" + ", ".join(_scalar(v) for v in value) + "]"
    return str(value)


def _allowed(field: dataclasses.Field[Any], hint: Any) -> str:
    if typing.get_origin(hint) is Literal:
        return "one of " + ", ".join(str(a) for a in typing.get_args(hint))
    if hint is bool:
        return "true or false"
    limits = describe_limits(field.metadata)
    return "" if limits == "any" else limits


def _comment(field: dataclasses.Field[Any], hint: Any, indent: str) -> list[str]:
    words = field.metadata.get("help", "")
    lines = textwrap.wrap(
        words, _WIDTH, initial_indent=f"{indent}# ", subsequent_indent=f"{indent}# "
    )
    allowed = _allowed(field, hint)
    has_default = field.default is not dataclasses.MISSING
    facts = [f"allowed: {allowed}"] if allowed else []
    facts += [f"default: {_scalar(field.default)}"] if has_default else []
    if facts and words:
        lines.append(f"{indent}#   " + "; ".join(facts))
    return lines


def _is_records(hint: Any) -> bool:
    args = typing.get_args(hint)
    return typing.get_origin(hint) is tuple and bool(args) and dataclasses.is_dataclass(args[0])


def _block(obj: Any, indent: str) -> list[str]:
    lines: list[str] = []
    hints = typing.get_type_hints(type(obj))
    for field in dataclasses.fields(obj):
        value, hint = getattr(obj, field.name), hints[field.name]
        if dataclasses.is_dataclass(hint):
            lines += ["", f"{indent}# {type(value).__doc__}", f"{indent}{field.name}:"]
            lines += _block(value, indent + "  ")
        elif _is_records(hint):
            lines += ["", f"{indent}# {typing.get_args(hint)[0].__doc__} Each has:"]
            record = typing.get_args(hint)[0]
            for item_field in dataclasses.fields(record):
                allowed = _allowed(item_field, typing.get_type_hints(record)[item_field.name])
                words = item_field.metadata.get("help", "") + (f" ({allowed})" if allowed else "")
                lines.append(f"{indent}#   {item_field.name}: {words}")
            lines.append(f"{indent}{field.name}:")
            for item in value:
                item_lines = _block(item, indent + "    ")
                plain = [x for x in item_lines if x.strip() and not x.lstrip().startswith("#")]
                lines += [f"{indent}  - {plain[0].strip()}", *plain[1:]]
        else:
            if indent == "":
                lines.append("")
            lines += _comment(field, hint, indent)
            lines += _value_lines(field.name, value, indent)
    return lines


def _value_lines(name: str, value: Any, indent: str) -> list[str]:
    if isinstance(value, tuple) and value and all(isinstance(v, str) for v in value):
        return [f"{indent}{name}:"] + [f"{indent}  - {v}" for v in value]
    return [f"{indent}{name}: {_scalar(value)}"]


def commented_yaml(settings: Any, header: str) -> str:
    """Return the YAML text of `settings` with the schema's comments under `header`."""
    head = [f"# {line}".rstrip() for line in header.strip().splitlines()]
    lines = head + _block(settings, "")
    return "\n".join(lines).replace("\n\n\n", "\n\n") + "\n"


def settings_rows(file: str, schema: type, prefix: str = "") -> list[str]:
    """Return the settings table's rows for `schema`: key, meaning, allowed values, default."""
    rows = []
    hints = typing.get_type_hints(schema)
    for field in dataclasses.fields(schema):
        key, hint = f"{prefix}{field.name}", hints[field.name]
        if isinstance(hint, type) and dataclasses.is_dataclass(hint):
            rows += settings_rows(file, hint, f"{key}.")
            continue
        default = field.default
        if _is_records(hint):
            shown = f"{len(default)} items" if default is not dataclasses.MISSING else "required"
            doc = typing.get_args(hint)[0].__doc__
            rows.append(f"| `{file}` | `{key}` | {doc} | a list | {shown} |")
            continue
        shown = "required" if default is dataclasses.MISSING else f"`{_scalar(default)}`"
        allowed = _allowed(field, hint) or "any"
        words = field.metadata.get("help", "")
        rows.append(f"| `{file}` | `{key}` | {words} | {allowed} | {shown} |")
    return rows
