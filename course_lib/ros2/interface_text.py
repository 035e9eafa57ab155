"""Render `ros2 interface show` from interface files (pure): comments, nesting, tabs.

Each line is judged alone by rosidl_adapter's parser, as ros2interface does: a comment line,
a field's trailing comment (cut with `--no-comments`), and a field of a message type, which
is followed by that type's definition, one tab deeper.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass

from rosidl_adapter.parser import parse_message_string

__all__ = ["show_lines"]

SEPARATORS = ("---",)  # between request and response (and an action's feedback)


@dataclass(frozen=True)
class _Line:
    """What rosidl_adapter makes of one line of an interface file."""

    is_comment: bool = False
    trailing: str | None = None  # a field's or constant's own comment
    nested: str | None = None  # `pkg/msg/Type` of a field of a message type


def _judge(line: str, package: str) -> _Line:
    if line in SEPARATORS:
        return _Line()
    spec = parse_message_string(package, "X", line)
    element = (spec.fields or spec.constants or [None])[0]
    trailing = element.annotations.get("comment") if element is not None else None
    field_type = str(spec.fields[0].type) if spec.fields else ""
    return _Line(
        is_comment=bool(spec.annotations["comment"]),
        trailing=trailing[0] if trailing else None,
        nested=field_type.split("[")[0].replace("/", "/msg/") if "/" in field_type else None,
    )


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
        judged = _judge(line, parts[0])
        if not comments:
            if not text or judged.is_comment:
                continue
            if judged.trailing is not None:
                text = text[: text.find(judged.trailing) - 1].strip()
        yield "\t" * depth + text if text else ""
        nested = judged.nested
        if nested:
            yield from show_lines(
                nested,
                read,
                comments=nested_comments,
                nested_comments=nested_comments,
                depth=depth + 1,
            )
