"""`DeclareLaunchArgument`: a launch file's arguments (`name:=value`), with defaults."""

from __future__ import annotations

from typing import Any

from .entity import Action
from .substitution import as_text, normalize_to_list_of_substitutions, perform_substitutions

__all__ = ["DeclareLaunchArgument"]


class DeclareLaunchArgument(Action):
    """Declare a launch argument (`name:=value` on the command line), with a default."""

    def __init__(
        self,
        name: str,
        *,
        default_value: Any = None,
        description: str | None = None,
        choices: list[str] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.name = name
        self.default_value = (
            None
            if default_value is None
            else normalize_to_list_of_substitutions(as_text(default_value))
        )
        if choices is not None and len(choices) == 0:
            raise RuntimeError(
                "Provided choices arg is empty. Use None to ignore the choice list."
            )
        if choices is not None and isinstance(default_value, str) and default_value not in choices:
            raise RuntimeError(
                f'Provided default_value "{default_value}" is not in provided choices "{choices}".'
            )
        if description is None:
            self.description = (
                "no description given" if choices is None else ("One of: " + str(choices))
            )
        else:
            self.description = description
            if choices is not None:
                self.description += "" if self.description.endswith(".") else "."
                self.description += " Valid choices are: " + str(choices)
        self.choices = choices
        self._conditionally_included = False

    def execute(self, context: Any) -> None:
        if self.name not in context.launch_configurations:
            if self.default_value is None:
                context.log(
                    "launch.actions.declare_launch_argument",
                    "ERROR",
                    f'Required launch argument "{self.name}" (description: '
                    f'"{self.description}") was not provided',
                )
                raise RuntimeError(f'Required launch argument "{self.name}" was not provided.')
            context.launch_configurations[self.name] = perform_substitutions(
                context, self.default_value
            )
        value = context.launch_configurations[self.name]
        if self.choices is not None and value not in self.choices:
            message = (
                f'Argument "{self.name}" provided value "{value}" is not valid. '
                f"Valid options are: {self.choices}"
            )
            context.log("launch.actions.declare_launch_argument", "ERROR", message)
            raise RuntimeError(message)
