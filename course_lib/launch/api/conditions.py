"""Conditions of `launch.conditions`: `condition=IfCondition(...)` and friends."""

from __future__ import annotations

import warnings
from typing import Any

from ..core.entity import Condition
from ..core.substitution import (
    Substitution,
    describe_all,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)
from .exposure import expose

__all__ = [
    "IfCondition",
    "InvalidConditionExpressionError",
    "LaunchConfigurationEquals",
    "LaunchConfigurationNotEquals",
    "UnlessCondition",
    "evaluate_condition_expression",
]

VALID_TRUE = ("true", "1")
VALID_FALSE = ("false", "0")


@expose("launch.conditions")
class InvalidConditionExpressionError(ValueError):
    """A condition's text is none of true, 1, false, 0."""

    def __init__(self, expression: str, unexpanded: list[Substitution]) -> None:
        super().__init__(
            f"invalid condition expression, expected one of "
            f"[{', '.join((*VALID_TRUE, *VALID_FALSE))}] but got '{expression}', "
            f"expanded from '{describe_all(unexpanded)}'"
        )


@expose("launch.conditions")
def evaluate_condition_expression(context: Any, expression: list[Substitution]) -> bool:
    """Return the truth of a condition's text (`true`/`1`, `false`/`0`, any case)."""
    text = perform_substitutions(context, expression).strip().lower()
    if text in VALID_TRUE:
        return True
    if text in VALID_FALSE:
        return False
    raise InvalidConditionExpressionError(text, expression)


@expose("launch.conditions")
class IfCondition(Condition):
    """Run the action when the expression is true."""

    def __init__(self, predicate_expression: Any) -> None:
        expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(lambda context: evaluate_condition_expression(context, expression))


@expose("launch.conditions")
class UnlessCondition(Condition):
    """Run the action when the expression is false."""

    def __init__(self, predicate_expression: Any) -> None:
        expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(lambda context: not evaluate_condition_expression(context, expression))


_DEPRECATED = (
    "The 'LaunchConfigurationEquals' and 'LaunchConfigurationNotEquals' Conditions are  "
    "deprecated. Use the 'EqualsSubstitution' and 'NotEqualsSubstitution' substitutions "
    "instead! E.g.:\n  IfCondition(\n  \tEqualsSubstitution(LaunchConfiguration("
    "'some_launch_arg'), \"some_equality_check\")\n  )"
)


class _ConfigurationCondition(Condition):
    def __init__(self, name: str, expected_value: Any, *, negate: bool) -> None:
        warnings.warn(_DEPRECATED, UserWarning, stacklevel=3)
        self.name = name
        self.expected = (
            None if expected_value is None else normalize_to_list_of_substitutions(expected_value)
        )
        super().__init__(lambda context: self._equals(context) != negate)

    def _equals(self, context: Any) -> bool:
        expected = None if self.expected is None else perform_substitutions(context, self.expected)
        if self.name not in context.launch_configurations:
            return expected is None
        return context.launch_configurations[self.name] == expected


@expose("launch.conditions")
class LaunchConfigurationEquals(_ConfigurationCondition):
    """True when a launch configuration equals a value (None: when it is not set)."""

    def __init__(self, launch_configuration_name: str, expected_value: Any) -> None:
        super().__init__(launch_configuration_name, expected_value, negate=False)


@expose("launch.conditions")
class LaunchConfigurationNotEquals(_ConfigurationCondition):
    """True when a launch configuration differs from a value (None: when it is set)."""

    def __init__(self, launch_configuration_name: str, expected_value: Any) -> None:
        super().__init__(launch_configuration_name, expected_value, negate=True)
