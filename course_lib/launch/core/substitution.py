"""Core of substitutions: the base class, plain text, and turning values into substitutions."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

__all__ = [
    "Substitution",
    "SubstitutionFailure",
    "TextSubstitution",
    "as_text",
    "describe_all",
    "normalize_to_list_of_substitutions",
    "perform_substitutions",
]


class SubstitutionFailure(RuntimeError):
    """A substitution could not be performed (missing configuration, variable, ...)."""


class Substitution:
    """Base of every substitution: `perform(context)` returns text."""

    def perform(self, context: Any) -> str:
        """Return the text this substitution stands for."""
        raise NotImplementedError

    def describe(self) -> str:
        """Return a short description, as `--show-args` prints it."""
        return repr(self)

    def __str__(self) -> str:
        return self.describe()


class TextSubstitution(Substitution):
    """Plain text."""

    def __init__(self, *, text: str) -> None:
        if not isinstance(text, str):
            raise TypeError(f"TextSubstitution expected Text object got '{type(text)}' instead.")
        self.text = text

    def perform(self, context: Any) -> str:
        return self.text

    def describe(self) -> str:
        return f"'{self.text}'"


def normalize_to_list_of_substitutions(value: Any) -> list[Substitution]:
    """Turn text, a substitution or an iterable of both into a list of substitutions."""
    if isinstance(value, str):
        return [TextSubstitution(text=value)]
    if isinstance(value, Substitution):
        return [value]
    if isinstance(value, os.PathLike):
        return [TextSubstitution(text=os.fspath(value))]
    if isinstance(value, Iterable):
        result: list[Substitution] = []
        for item in value:
            result.extend(normalize_to_list_of_substitutions(item))
        return result
    raise TypeError(
        f"value '{value}' is not a str, Substitution or iterable of them ({type(value)})"
    )


def perform_substitutions(context: Any, subs: Iterable[Substitution]) -> str:
    """Perform each substitution and join the texts."""
    return "".join(sub.perform(context) for sub in subs)


def describe_all(subs: Iterable[Substitution]) -> str:
    """Describe substitutions as launch joins them (`a + b`)."""
    return " + ".join(sub.describe() for sub in subs)


def as_text(value: Any) -> Any:
    """Return numbers and booleans as text (launch arguments, periods); keep the rest."""
    return str(value) if isinstance(value, (bool, int, float)) else value
