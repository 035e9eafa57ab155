"""Actions of `launch.actions` (except ExecuteProcess, in process.py)."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from typing import Any

from .description import Action, LaunchDescriptionSource
from .substitutions import normalize_to_list_of_substitutions, perform_substitutions

__all__ = [
    "DeclareLaunchArgument",
    "GroupAction",
    "IncludeLaunchDescription",
    "LogInfo",
    "OpaqueFunction",
    "SetEnvironmentVariable",
    "SetLaunchConfiguration",
    "Shutdown",
    "TimerAction",
]


def _text(value: Any) -> Any:
    return str(value) if isinstance(value, (bool, int, float)) else value


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
            else normalize_to_list_of_substitutions(_text(default_value))
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


class SetLaunchConfiguration(Action):
    """Set a launch configuration (XML/YAML `let`)."""

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(_text(value))

    def execute(self, context: Any) -> None:
        context.launch_configurations[perform_substitutions(context, self.name)] = (
            perform_substitutions(context, self.value)
        )


class IncludeLaunchDescription(Action):
    """Include another launch file, passing it launch arguments."""

    def __init__(
        self,
        launch_description_source: Any,
        *,
        launch_arguments: Iterable[tuple[Any, Any]] | dict | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        if not isinstance(launch_description_source, LaunchDescriptionSource):
            from .description import AnyLaunchDescriptionSource

            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self.launch_description_source = launch_description_source
        items = (
            launch_arguments.items()
            if isinstance(launch_arguments, dict)
            else (launch_arguments or [])
        )
        self.launch_arguments = [(k, _text(v)) for k, v in items]

    def describe_sub_entities(self) -> list[Any]:
        found = self.launch_description_source.try_get_launch_description_without_context()
        return [found] if found is not None else []

    def execute(self, context: Any) -> list[Any]:
        description = self.launch_description_source.get_launch_description(context)
        location = self.launch_description_source.location
        context.extend_locals(
            {
                "current_launch_file_path": location,
                "current_launch_file_directory": (
                    os.path.dirname(location) if os.path.exists(location) else location
                ),
            }
        )
        given = [
            perform_substitutions(context, normalize_to_list_of_substitutions(name))
            for name, _ in self.launch_arguments
        ]
        for argument in description.get_launch_arguments():
            if argument._conditionally_included or argument.default_value is not None:
                continue
            if argument.name not in given and argument.name not in context.launch_configurations:
                raise RuntimeError(
                    f"Included launch description missing required argument '{argument.name}' "
                    f"(description: '{argument.description}'), given: [{', '.join(given)}]"
                )
        sets = [SetLaunchConfiguration(name, value) for name, value in self.launch_arguments]
        return [*sets, description]


class _Scope(Action):
    def __init__(self, push: bool) -> None:
        super().__init__()
        self.push = push

    def execute(self, context: Any) -> None:
        if self.push:
            context.push_launch_configurations()
            context.push_environment()
        else:
            context.pop_launch_configurations()
            context.pop_environment()


class GroupAction(Action):
    """Group actions, scoping the launch configurations they set."""

    def __init__(
        self,
        actions: Iterable[Any],
        *,
        scoped: bool = True,
        launch_configurations: dict | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.actions = list(actions)
        self.scoped = scoped
        self.launch_configurations = dict(launch_configurations or {})

    def describe_sub_entities(self) -> list[Any]:
        return list(self.actions)

    def execute(self, context: Any) -> list[Any]:
        sets = [SetLaunchConfiguration(k, v) for k, v in self.launch_configurations.items()]
        if not self.scoped:
            return [*sets, *self.actions]
        return [_Scope(True), *sets, *self.actions, _Scope(False)]


class LogInfo(Action):
    """Log a message as `[INFO] [launch.user]: ...`."""

    def __init__(self, *, msg: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.msg = normalize_to_list_of_substitutions(msg)

    def execute(self, context: Any) -> None:
        context.log("launch.user", "INFO", perform_substitutions(context, self.msg))


class TimerAction(Action):
    """Visit actions after a period (seconds), unless the launch shuts down first."""

    def __init__(
        self,
        *,
        period: Any,
        actions: Iterable[Any],
        cancel_on_shutdown: bool = True,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.period = normalize_to_list_of_substitutions(_text(period))
        self.actions = list(actions)
        self.cancel_on_shutdown = cancel_on_shutdown

    def describe_sub_entities(self) -> list[Any]:
        return list(self.actions)

    def execute(self, context: Any) -> list[Any] | None:
        period = float(perform_substitutions(context, self.period))
        if context.runtime is None:  # describing only: the actions happen, later
            return list(self.actions)
        context.runtime.add_timer(period, self.actions, self.cancel_on_shutdown)
        return None


class OpaqueFunction(Action):
    """Call a function with the context; it may return more actions."""

    def __init__(
        self,
        *,
        function: Callable[..., Any],
        args: Iterable[Any] | None = None,
        kwargs: dict | None = None,
        **action_kwargs: Any,
    ) -> None:
        super().__init__(**action_kwargs)
        self.function = function
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})

    def execute(self, context: Any) -> list[Any] | None:
        return self.function(context, *self.args, **self.kwargs)


class SetEnvironmentVariable(Action):
    """Set an environment variable for the processes started after it."""

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(_text(value))

    def execute(self, context: Any) -> None:
        context.environment[perform_substitutions(context, self.name)] = perform_substitutions(
            context, self.value
        )


class Shutdown(Action):
    """Shut the whole launch down."""

    def __init__(self, *, reason: str = "reason not given", **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.reason = reason

    def execute(self, context: Any) -> None:
        if context.runtime is not None:
            context.runtime.request_shutdown(self.reason)
