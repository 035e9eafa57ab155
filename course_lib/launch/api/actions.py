"""Actions of `launch.actions` (except ExecuteProcess, in process.py)."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from typing import Any

from ..core.description import AnyLaunchDescriptionSource, LaunchDescriptionSource
from ..core.entity import Action
from ..core.launch_argument import DeclareLaunchArgument
from ..core.substitution import as_text, normalize_to_list_of_substitutions, perform_substitutions
from .exposure import expose, expose_action

__all__ = [
    "DeclareLaunchArgument",
    "GroupAction",
    "IncludeLaunchDescription",
    "LogInfo",
    "OpaqueFunction",
    "SetEnvironmentVariable",
    "SetLaunchConfiguration",
    "TimerAction",
]


@expose_action("let")
class SetLaunchConfiguration(Action):
    """Set a launch configuration (XML/YAML `let`)."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<let name= value=/>`."""
        name, value = parser.subs(entity, "name", False), parser.subs(entity, "value", False)
        return cls(name, value, **parser.condition(entity))

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(as_text(value))

    def execute(self, context: Any) -> None:
        context.launch_configurations[perform_substitutions(context, self.name)] = (
            perform_substitutions(context, self.value)
        )


@expose_action("include")
class IncludeLaunchDescription(Action):
    """Include another launch file, passing it launch arguments."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<include file=>` with `<arg name= value=/>` children."""
        args = entity.get_attr("arg", data_type=list, optional=True) or []
        return cls(
            AnyLaunchDescriptionSource(parser.subs(entity, "file", optional=False)),
            launch_arguments=[
                (parser.subs(a, "name", False), parser.subs(a, "value", False)) for a in args
            ],
            **parser.condition(entity),
        )

    def __init__(
        self,
        launch_description_source: Any,
        *,
        launch_arguments: Iterable[tuple[Any, Any]] | dict | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        if not isinstance(launch_description_source, LaunchDescriptionSource):
            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self.launch_description_source = launch_description_source
        items = (
            launch_arguments.items()
            if isinstance(launch_arguments, dict)
            else (launch_arguments or [])
        )
        self.launch_arguments = [(k, as_text(v)) for k, v in items]

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
    """Push or pop launch configurations and environment; optionally reset them."""

    def __init__(self, push: bool, reset: dict | None = None) -> None:
        super().__init__()
        self.push = push
        self.reset = reset

    def execute(self, context: Any) -> None:
        if not self.push:
            context.pop_launch_configurations()
            context.pop_environment()
            return
        context.push_launch_configurations()
        context.push_environment()
        if self.reset is not None:  # forwarding=False: the group starts afresh
            values = {
                perform_substitutions(context, normalize_to_list_of_substitutions(k)): (
                    perform_substitutions(context, normalize_to_list_of_substitutions(v))
                )
                for k, v in self.reset.items()
            }
            context.launch_configurations.clear()
            context.launch_configurations.update(values)
            context.environment.clear()
            context.environment.update(context.initial_environment)


@expose_action("group")
class GroupAction(Action):
    """Group actions, scoping the launch configurations they set."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<group scoped=>` with its actions as children."""
        return cls(
            [parser.parse_action(c) for c in entity.children if c.type_name != "env"],
            scoped=entity.get_attr("scoped", data_type=bool, optional=True) is not False,
            **parser.condition(entity),
        )

    def __init__(
        self,
        actions: Iterable[Any],
        *,
        scoped: bool = True,
        forwarding: bool = True,
        launch_configurations: dict | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.actions = list(actions)
        self.scoped = scoped
        self.forwarding = forwarding
        self.launch_configurations = dict(launch_configurations or {})

    def describe_sub_entities(self) -> list[Any]:
        return list(self.actions)

    def execute(self, context: Any) -> list[Any]:
        sets = [SetLaunchConfiguration(k, v) for k, v in self.launch_configurations.items()]
        if not self.scoped:
            return [*sets, *self.actions]
        if not self.forwarding:
            return [_Scope(True, self.launch_configurations), *self.actions, _Scope(False)]
        return [_Scope(True), *sets, *self.actions, _Scope(False)]


@expose_action("log")
class LogInfo(Action):
    """Log a message as `[INFO] [launch.user]: ...`."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<log message=/>`."""
        return cls(msg=parser.subs(entity, "message", False), **parser.condition(entity))

    def __init__(self, *, msg: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.msg = normalize_to_list_of_substitutions(msg)

    def execute(self, context: Any) -> None:
        context.log("launch.user", "INFO", perform_substitutions(context, self.msg))


@expose_action("timer")
class TimerAction(Action):
    """Visit actions after a period (seconds), unless the launch shuts down first."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<timer period=>` with its actions as children."""
        return cls(
            period=parser.subs(entity, "period", False),
            actions=[parser.parse_action(c) for c in entity.children],
            **parser.condition(entity),
        )

    def __init__(
        self,
        *,
        period: Any,
        actions: Iterable[Any],
        cancel_on_shutdown: bool = True,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.period = normalize_to_list_of_substitutions(as_text(period))
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


@expose("launch.actions")
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


@expose_action("set_env")
class SetEnvironmentVariable(Action):
    """Set an environment variable for the processes started after it."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<set_env name= value=/>`."""
        name, value = parser.subs(entity, "name", False), parser.subs(entity, "value", False)
        return cls(name, value, **parser.condition(entity))

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(as_text(value))

    def execute(self, context: Any) -> None:
        context.environment[perform_substitutions(context, self.name)] = perform_substitutions(
            context, self.value
        )


def _parse_declare_argument(entity: Any, parser: Any) -> DeclareLaunchArgument:
    """`<arg name= default= description=/>` (DeclareLaunchArgument lives in launch/core)."""
    default = entity.get_attr("default", optional=True)
    return DeclareLaunchArgument(
        str(entity.get_attr("name")),
        default_value=None if default is None else parser.parse_substitution(str(default)),
        description=entity.get_attr("description", optional=True),
        **parser.condition(entity),
    )


expose_action("arg", parse=_parse_declare_argument)(DeclareLaunchArgument)
