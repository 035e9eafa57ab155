"""Name the line a YAML syntax error really is on, in words an instructor reads (pure).

PyYAML reports where its parser gave up, which is often lines after the mistake: a key
without its colon on line 7 followed by comments is reported at line 10 ("expected
'<document start>'"), an unclosed `[` at the next key. This module points at the mistake.
"""

from __future__ import annotations

import re

import yaml

__all__ = ["syntax_problem"]

# A line of a block mapping that has a key-like word but no `key:` colon: `velocity 0.2`.
_NO_COLON = re.compile(r"^\s*(?!-\s)(?![\[{])[A-Za-z_][\w.-]*(\s+\S.*)?$")


def _content(line: str) -> str:
    return line.split(" #", 1)[0].rstrip() if not line.lstrip().startswith("#") else ""


def _line_without_colon(lines: list[str], last: int) -> int | None:
    """Return the 1-based number of the first key line up to `last` that lacks its colon."""
    depth = 0  # inside [ ] or { } a bare word is a value, not a key
    previous = ""  # a line indented past a `key: value` line continues that value
    for number, line in enumerate(lines[:last], 1):
        text = _content(line)
        if not text:
            continue
        indent = len(text) - len(text.lstrip())
        opens_block = previous.endswith(":") or not previous
        indented_past = indent > len(previous) - len(previous.lstrip())
        key_line = opens_block or not indented_past
        if depth == 0 and key_line and ":" not in text and _NO_COLON.match(text):
            return number
        depth += text.count("[") + text.count("{") - text.count("]") - text.count("}")
        previous = text
    return None


def _unclosed_bracket(lines: list[str], last: int) -> int | None:
    """Return the 1-based line of the first `[` or `{` still open at line `last`."""
    opened: list[int] = []
    for number, line in enumerate(lines[:last], 1):
        for char in _content(line):
            if char in "[{":
                opened.append(number)
            elif char in "]}" and opened:
                opened.pop()
    return opened[0] if opened else None


def syntax_problem(text: str, err: yaml.YAMLError) -> tuple[int | None, str]:
    """Return (line, problem) for a YAML syntax error in `text`, the line being the mistake's."""
    mark = getattr(err, "problem_mark", None)
    problem = getattr(err, "problem", None) or str(err)
    line = mark.line + 1 if mark is not None else None
    lines = text.splitlines()
    bare = _line_without_colon(lines, line or len(lines))
    if bare is not None:
        return bare, f"`{_content(lines[bare - 1]).strip()}` has no colon after its key"
    context = getattr(err, "context", None) or ""
    context_mark = getattr(err, "context_mark", None)
    opened = _unclosed_bracket(lines, line or len(lines))
    if "flow" in context and opened is not None:
        return opened, f"{problem} (the bracket opened on line {opened} is not closed)"
    if context_mark is not None and "simple key" in context:
        return context_mark.line + 1, problem
    return line, problem
