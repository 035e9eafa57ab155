"""Render `ros2 interface show` from interface files (pure): comments, nesting, tabs.

Each line is judged alone, as ros2interface does with rosidl_adapter: a line starting with
`#` is a comment unless nothing but `#`s (and a unit like `[m]`) is on it; a field's
trailing comment is cut with `--no-comments`; a field of a message type is followed by
that type's definition, one tab deeper.
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Callable, Iterator

__all__ = ["show_lines"]

SEPARATORS = ("---",)
_INTS = (f"{sign}int{bits}" for sign in ("", "u") for bits in (8, 16, 32, 64))
PRIMITIVES = frozenset(("bool", "byte", "char", "float32", "float64", "string", "wstring", *_INTS))
_UNIT = re.compile(r"(\s*\[([^,\]]+)\])")


def _annotation(comment: str) -> str | None:
    """Return the comment rosidl_adapter keeps (unit removed, dedented), None if none."""
    matches = _UNIT.findall(comment)
    if len(matches) == 1:
        comment = comment.replace(matches[0][0], "")
    return textwrap.dedent(comment) if comment != "" else None


def _split(line: str) -> tuple[str, str | None]:
    """Return (definition, comment or None) of one line (tabs count as spaces)."""
    line = line.replace("\t", " ")
    index = line.find("#")
    if index < 0:
        return line, None
    return line[:index], line[index:].lstrip("#")


def _is_comment(line: str) -> bool:
    return line.startswith("#") and _annotation(line.lstrip("#")) is not None


def _trailing(line: str) -> str | None:
    if line.startswith("#"):
        return None
    definition, comment = _split(line)
    if comment is None or " " not in definition.strip():
        return None
    return _annotation(comment)


def _nested(line: str, package: str) -> str | None:
    """Return `pkg/msg/Type` if the line is a field of a message type, else None."""
    if line.startswith("#") or line in SEPARATORS:
        return None
    definition = _split(line)[0].strip()
    type_string, _, rest = definition.partition(" ")
    if not rest.strip() or "=" in rest:
        return None  # no field, or a constant
    base = type_string.split("[", 1)[0].split("<=", 1)[0]
    if base in PRIMITIVES:
        return None
    full = base if "/" in base else f"{package}/{base}"
    return full.replace("/", "/msg/", 1)


def show_lines(
    name: str,
    read: Callable[[str], str],
    *,
    comments: bool = True,
    nested_comments: bool = False,
    depth: int = 0,
) -> Iterator[str]:
    """Yield the lines `ros2 interface show` prints for `pkg/kind/Name` (read gives text)."""
    parts = name.split("/")
    if len(parts) != 3:
        raise ValueError(f"Invalid name '{name}'. Expected three parts separated by '/'")
    for raw in read(name).splitlines():
        line = raw.rstrip()
        text = line
        if not comments:
            if not text or _is_comment(line):
                continue
            trailing = _trailing(line)
            if trailing is not None:
                text = text[: text.find(trailing) - 1].strip()
        yield "\t" * depth + text if text else ""
        nested = _nested(line, parts[0])
        if nested:
            yield from show_lines(
                nested,
                read,
                comments=nested_comments,
                nested_comments=nested_comments,
                depth=depth + 1,
            )
