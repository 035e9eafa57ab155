"""The `$(name arg ...)` substitution language of XML and YAML launch files.

Each `$(name ...)` is the substitution class that exposes it (`@expose_substitution("name")`
in substitutions.py and logic_substitutions.py), built by the class's `parse`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..core.loading import CourseUnavailableError
from ..core.real_names import REAL_FRONTEND_SUBSTITUTIONS
from ..core.substitution import Substitution, TextSubstitution
from . import logic_substitutions, substitutions  # noqa: F401  (they expose their `$(...)`)
from .exposure import Args, frontend_substitutions

__all__ = ["parse_if_substitutions", "parse_substitution"]


def _fragment(text: str, i: int, stop: Callable[[str], bool]) -> tuple[list[Substitution], int]:
    """Parse text and nested `$(...)` until `stop(char)`; return (substitutions, index)."""
    out: list[Substitution] = []
    buf: list[str] = []
    while i < len(text) and not stop(text[i]):
        if text.startswith("\\$", i):
            buf.append("$")
            i += 2
        elif text.startswith("$(", i):
            if buf:
                out.append(TextSubstitution(text="".join(buf)))
                buf = []
            sub, i = _substitution(text, i + 2)
            out.append(sub)
        else:
            buf.append(text[i])
            i += 1
    if buf:
        out.append(TextSubstitution(text="".join(buf)))
    return out, i


def _substitution(text: str, i: int) -> tuple[Substitution, int]:
    start = i
    while i < len(text) and not text[i].isspace() and text[i] != ")":
        i += 1
    name = text[start:i]
    args: Args = []
    while True:
        while i < len(text) and text[i].isspace():
            i += 1
        if i >= len(text):
            raise ValueError(f"unterminated substitution '$({text[start:]}'")
        if text[i] == ")":
            break
        if text[i] in "'\"":
            quote = text[i]
            arg, i = _fragment(text, i + 1, quote.__eq__)
            i += 1
        else:
            arg, i = _fragment(text, i, lambda c: c.isspace() or c == ")")
        args.append(arg)
    makers = frontend_substitutions()
    if name not in makers:
        if name in REAL_FRONTEND_SUBSTITUTIONS:
            raise CourseUnavailableError(
                f"'$({name} ...)' is not available in this course; it has: "
                f"{', '.join(sorted(makers))}"
            )
        raise RuntimeError(f"Unknown substitution: {name}")
    return makers[name](args), i + 1


def parse_substitution(text: str) -> list[Substitution]:
    """Parse `text` with `$(...)` substitutions into a list of substitutions."""
    subs, _ = _fragment(text, 0, lambda c: False)
    return subs or [TextSubstitution(text="")]


def parse_if_substitutions(value: Any) -> Any:
    """Parse strings (and lists of strings) for substitutions; keep other values."""
    if isinstance(value, str):
        return parse_substitution(value)
    if isinstance(value, list):
        return [parse_if_substitutions(v) for v in value]
    return value
