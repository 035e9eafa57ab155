"""Boolean substitutions of `launch.substitutions`: Not, And, Or, Any, All, IfElse."""

from __future__ import annotations

from typing import Any

import yaml

from ..core.substitution import (
    Substitution,
    SubstitutionFailure,
    describe_all,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "AllSubstitution",
    "AndSubstitution",
    "AnySubstitution",
    "IfElseSubstitution",
    "NotSubstitution",
    "OrSubstitution",
    "perform_bool",
]


def perform_bool(context: Any, subs: list[Substitution]) -> bool:
    """Perform `subs` and read the text as launch reads a bool (YAML rules, and 1/0)."""
    text = perform_substitutions(context, subs)
    value = {"1": "true", "0": "false"}.get(text, text)
    try:
        result = yaml.safe_load(value)
    except yaml.YAMLError as exc:
        raise SubstitutionFailure(
            f"Failed to convert '{value}' to '{bool}': yaml.safe_load() failed\n{exc}"
        ) from None
    if not isinstance(result, bool):
        raise SubstitutionFailure(f"Cannot convert value '{value}' to '{bool}'")
    return result


def _subs(value: Any) -> list[Substitution]:
    return normalize_to_list_of_substitutions(value)


class NotSubstitution(Substitution):
    """`true` when the value is false."""

    def __init__(self, value: Any) -> None:
        self.value = _subs(value)

    def perform(self, context: Any) -> str:
        return str(not perform_bool(context, self.value)).lower()

    def describe(self) -> str:
        return f"NotSubstitution({describe_all(self.value)})"


class AndSubstitution(Substitution):
    """`true` when both sides are true."""

    def __init__(self, left: Any, right: Any) -> None:
        self.left, self.right = _subs(left), _subs(right)

    def perform(self, context: Any) -> str:
        left, right = perform_bool(context, self.left), perform_bool(context, self.right)
        return str(left and right).lower()

    def describe(self) -> str:
        return f"AndSubstitution({describe_all(self.left)} {describe_all(self.right)})"


class OrSubstitution(AndSubstitution):
    """`true` when either side is true."""

    def perform(self, context: Any) -> str:
        left, right = perform_bool(context, self.left), perform_bool(context, self.right)
        return str(left or right).lower()


class AnySubstitution(Substitution):
    """`true` when at least one argument is true."""

    def __init__(self, *args: Any) -> None:
        self.args = [_subs(arg) for arg in args]

    def perform(self, context: Any) -> str:
        return str(any([perform_bool(context, arg) for arg in self.args])).lower()


class AllSubstitution(AnySubstitution):
    """`true` when every argument is true."""

    def perform(self, context: Any) -> str:
        return str(all([perform_bool(context, arg) for arg in self.args])).lower()


class IfElseSubstitution(Substitution):
    """`if_value` when the condition is true, else `else_value`."""

    def __init__(self, condition: Any, if_value: Any = "", else_value: Any = "") -> None:
        if if_value == else_value == "":
            raise RuntimeError("One of if_value and else_value must be specified")
        self.condition = _subs(condition)
        self.if_value, self.else_value = _subs(if_value), _subs(else_value)

    def perform(self, context: Any) -> str:
        chosen = self.if_value if perform_bool(context, self.condition) else self.else_value
        return perform_substitutions(context, chosen)
