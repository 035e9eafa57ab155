"""Boolean substitutions of `launch.substitutions`: Not, And, Or, Any, All, IfElse, Equals and
NotEquals."""

from __future__ import annotations

import math
from typing import Any

import yaml

from ..core.substitution import (
    Substitution,
    SubstitutionFailure,
    as_text,
    describe_all,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)
from .exposure import Args, expect_arguments, expose_substitution

__all__ = [
    "AllSubstitution",
    "AndSubstitution",
    "AnySubstitution",
    "EqualsSubstitution",
    "IfElseSubstitution",
    "NotEqualsSubstitution",
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


@expose_substitution("not")
class NotSubstitution(Substitution):
    """`true` when the value is false."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(not value)`."""
        expect_arguments(name, args, 1)
        return cls(*args)

    def __init__(self, value: Any) -> None:
        self.value = _subs(value)

    def perform(self, context: Any) -> str:
        return str(not perform_bool(context, self.value)).lower()

    def describe(self) -> str:
        return f"NotSubstitution({describe_all(self.value)})"


@expose_substitution("and")
class AndSubstitution(Substitution):
    """`true` when both sides are true."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(and left right)` (and `or`, whose message launch words as `and`: sic)."""
        expect_arguments("and", args, 2)
        return cls(*args)

    def __init__(self, left: Any, right: Any) -> None:
        self.left, self.right = _subs(left), _subs(right)

    def perform(self, context: Any) -> str:
        left, right = perform_bool(context, self.left), perform_bool(context, self.right)
        return str(left and right).lower()

    def describe(self) -> str:
        return f"AndSubstitution({describe_all(self.left)} {describe_all(self.right)})"


@expose_substitution("or")
class OrSubstitution(AndSubstitution):
    """`true` when either side is true."""

    def perform(self, context: Any) -> str:
        left, right = perform_bool(context, self.left), perform_bool(context, self.right)
        return str(left or right).lower()


@expose_substitution("any")
class AnySubstitution(Substitution):
    """`true` when at least one argument is true."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(any value ...)` (and `all`)."""
        return cls(*args)

    def __init__(self, *args: Any) -> None:
        self.args = [_subs(arg) for arg in args]

    def perform(self, context: Any) -> str:
        return str(any([perform_bool(context, arg) for arg in self.args])).lower()


@expose_substitution("all")
class AllSubstitution(AnySubstitution):
    """`true` when every argument is true."""

    def perform(self, context: Any) -> str:
        return str(all([perform_bool(context, arg) for arg in self.args])).lower()


@expose_substitution("if")
class IfElseSubstitution(Substitution):
    """`if_value` when the condition is true, else `else_value`."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(if condition if_value [else_value])`."""
        if not 2 <= len(args) <= 3:
            raise TypeError("if substitution expects from 2 or 3 arguments")
        return cls(*args)

    def __init__(self, condition: Any, if_value: Any = "", else_value: Any = "") -> None:
        if if_value == else_value == "":
            raise RuntimeError("One of if_value and else_value must be specified")
        self.condition = _subs(condition)
        self.if_value, self.else_value = _subs(if_value), _subs(else_value)

    def perform(self, context: Any) -> str:
        chosen = self.if_value if perform_bool(context, self.condition) else self.else_value
        return perform_substitutions(context, chosen)


def _is_bool(text: str) -> bool:
    return text.lower() in ("true", "false", "1", "0")


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


@expose_substitution("equals")
class EqualsSubstitution(Substitution):
    """`true` when both sides are equal (as booleans, as numbers, else as text)."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(equals left right)` (and `not-equals`)."""
        # (sic) launch's own message names `and` for `$(equals ...)`
        expect_arguments("and" if name == "equals" else name, args, 2)
        return cls(*args)

    def __init__(self, left: Any, right: Any) -> None:
        self.left = normalize_to_list_of_substitutions(_as_text(left))
        self.right = normalize_to_list_of_substitutions(_as_text(right))

    def _equal(self, context: Any) -> bool:
        left = perform_substitutions(context, self.left)
        right = perform_substitutions(context, self.right)
        if _is_bool(left) and _is_bool(right):
            return (left.lower() in ("true", "1")) == (right.lower() in ("true", "1"))
        if _is_float(left) and _is_float(right):
            return math.isclose(float(left), float(right))
        return left == right

    def perform(self, context: Any) -> str:
        return str(self._equal(context)).lower()

    def describe(self) -> str:
        return f"EqualsSubstitution({describe_all(self.left)} {describe_all(self.right)})"


@expose_substitution("not-equals")
class NotEqualsSubstitution(EqualsSubstitution):
    """`true` when the sides differ."""

    def perform(self, context: Any) -> str:
        return str(not self._equal(context)).lower()

    def describe(self) -> str:
        return f"NotEqualsSubstitution({describe_all(self.left)} {describe_all(self.right)})"


def _as_text(value: Any) -> Any:
    if value is None:
        return ""
    return str(value).lower() if isinstance(value, bool) else as_text(value)
