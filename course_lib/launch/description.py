"""Launch descriptions, the action base class, conditions and launch file sources."""

from __future__ import annotations

import os
from collections.abc import Iterable
from importlib.machinery import SourceFileLoader
from importlib.util import module_from_spec, spec_from_loader
from typing import Any

from .substitutions import normalize_to_list_of_substitutions, perform_substitutions

__all__ = [
    "Action",
    "AnyLaunchDescriptionSource",
    "Condition",
    "FrontendLaunchDescriptionSource",
    "IfCondition",
    "InvalidFrontendLaunchFileError",
    "InvalidLaunchFileError",
    "InvalidPythonLaunchFileError",
    "LaunchDescription",
    "LaunchDescriptionEntity",
    "LaunchDescriptionSource",
    "PythonLaunchDescriptionSource",
    "UnlessCondition",
    "load_any_launch_file",
]

LOADED_LAUNCH_FILES: set[str] = set()  # paths evaluated so far, to name them in errors


class LaunchDescriptionEntity:
    """Anything a launch description may hold."""

    def visit(self, context: Any) -> list[Any] | None:
        """Apply this entity to the context; return the entities to visit next."""
        return None

    def describe_sub_entities(self) -> list[Any]:
        """Return the entities inside this one, known without a context."""
        return []


class Condition:
    """Decides at visit time whether an action runs."""

    def __init__(self, predicate: Any) -> None:
        self._predicate = predicate

    def evaluate(self, context: Any) -> bool:
        """Return whether the action should run."""
        return bool(self._predicate(context))


def _as_bool(context: Any, expression: list[Any]) -> bool:
    text = perform_substitutions(context, expression).strip().lower()
    if text in ("true", "1"):
        return True
    if text in ("false", "0"):
        return False
    raise ValueError(f"Unknown boolean value '{text}' in condition expression")


class IfCondition(Condition):
    """Run the action when the expression is true."""

    def __init__(self, predicate_expression: Any) -> None:
        expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(lambda context: _as_bool(context, expression))


class UnlessCondition(Condition):
    """Run the action when the expression is false."""

    def __init__(self, predicate_expression: Any) -> None:
        expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(lambda context: not _as_bool(context, expression))


class Action(LaunchDescriptionEntity):
    """An action: runs `execute` when its condition (if any) holds."""

    def __init__(self, *, condition: Condition | None = None) -> None:
        self.condition = condition

    def visit(self, context: Any) -> list[Any] | None:
        if self.condition is None or self.condition.evaluate(context):
            return self.execute(context)
        return None

    def execute(self, context: Any) -> list[Any] | None:
        """Do what the action does; return entities to visit next."""
        return None

    def describe(self) -> str:
        """Return a short description."""
        return f"{type(self).__name__}"


class LaunchDescription(LaunchDescriptionEntity):
    """An ordered list of actions, as `generate_launch_description()` returns."""

    def __init__(
        self,
        initial_entities: Iterable[Any] | None = None,
        *,
        deprecated_reason: str | None = None,
    ) -> None:
        self.entities = list(initial_entities or [])
        self.deprecated_reason = deprecated_reason

    def add_action(self, action: Any) -> None:
        """Append an action."""
        self.entities.append(action)

    def add_entity(self, entity: Any) -> None:
        """Append an entity."""
        self.entities.append(entity)

    def visit(self, context: Any) -> list[Any] | None:
        return list(self.entities)

    def describe_sub_entities(self) -> list[Any]:
        return list(self.entities)

    def get_launch_arguments(self, conditional_inclusion: bool = False) -> list[Any]:
        """Return the DeclareLaunchArgument actions, included files' too, first seen first."""
        from .actions import DeclareLaunchArgument

        found: list[Any] = []
        names: set[str] = set()

        def walk(entities: list[Any], conditional: bool) -> None:
            for entity in entities:
                if isinstance(entity, DeclareLaunchArgument) and entity.name not in names:
                    entity._conditionally_included = conditional
                    names.add(entity.name)
                    found.append(entity)
                cond = conditional or getattr(entity, "condition", None) is not None
                walk(entity.describe_sub_entities(), cond)

        walk(self.entities, conditional_inclusion)
        return found


class InvalidPythonLaunchFileError(Exception):
    """The Python launch file has no `generate_launch_description()`."""


class InvalidLaunchFileError(Exception):
    """No loader could read the launch file; lists what each loader raised."""

    def __init__(self, extension: str = "", *, likely_errors: list[Exception] | None = None):
        self.likely_errors = likely_errors or []
        if extension == "" or not self.likely_errors:
            message = "The launch file may have a syntax error, or its format is unknown"
        else:
            several = "multiple exceptions" if len(self.likely_errors) > 1 else "exception"
            message = f"Caught {several} when trying to load file of format [{extension}]:"
            for error in self.likely_errors:
                message += f"\n - {type(error).__name__}: {error}"
            self.__cause__ = self.likely_errors[0]
        super().__init__(message)
        self._message = message

    def __str__(self) -> str:
        return self._message


class InvalidFrontendLaunchFileError(InvalidLaunchFileError):
    """No front end (XML, YAML) could read the file."""


def load_python_launch_file(path: str) -> LaunchDescription:
    """Execute a Python launch file as a module and call `generate_launch_description()`."""
    from .shim import launch_modules

    LOADED_LAUNCH_FILES.add(os.path.abspath(path))
    loader = SourceFileLoader("python_launch_file", path)
    spec = spec_from_loader(loader.name, loader)
    if spec is None:
        raise RuntimeError("Failed to load module spec!")
    module = module_from_spec(spec)
    with launch_modules():
        loader.exec_module(module)
        if not hasattr(module, "generate_launch_description"):
            raise InvalidPythonLaunchFileError(
                f"launch file at '{path}' does not contain the required function "
                "'generate_launch_description()'"
            )
        return module.generate_launch_description()


def load_frontend_launch_file(path: str) -> LaunchDescription:
    """Parse an XML or YAML launch file."""
    from .frontend import load_frontend_file

    LOADED_LAUNCH_FILES.add(os.path.abspath(path))
    return load_frontend_file(path)


def load_any_launch_file(path: str) -> LaunchDescription:
    """Load a launch file, trying the loader its extension suggests first."""
    from .frontend import is_frontend_filename

    loaders = [load_frontend_launch_file]
    extension = os.path.splitext(os.path.basename(path))[1][1:]
    if extension == "py":
        loaders.insert(0, load_python_launch_file)
    else:
        loaders.append(load_python_launch_file)
        extension = extension if is_frontend_filename(os.path.basename(path)) else ""
    errors: list[Exception] = []
    for loader in loaders:
        try:
            return loader(path)
        except Exception as exc:
            errors.append(exc)
    raise InvalidLaunchFileError(extension, likely_errors=errors)


class LaunchDescriptionSource:
    """Where a launch description comes from; loads it when first needed."""

    def __init__(
        self,
        launch_description: LaunchDescription | None = None,
        location: Any = "<string>",
        method: str = "unspecified",
    ) -> None:
        self._description = launch_description
        self._location = normalize_to_list_of_substitutions(location)
        self._expanded: str | None = None
        self.method = method

    def _load(self, location: str) -> LaunchDescription:
        if self._description is None:
            raise RuntimeError("called without launch description being set")
        return self._description

    def get_launch_description(self, context: Any) -> LaunchDescription:
        """Return the launch description, loading the file if needed."""
        if self._expanded is None:
            self._expanded = perform_substitutions(context, self._location)
        if self._description is None:
            self._description = self._load(self._expanded)
        return self._description

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:
        """Return the description if it can be loaded without a context, else None."""
        if self._description is None:
            from .context import LaunchContext

            try:
                return self._load(perform_substitutions(LaunchContext(), self._location))
            except Exception:
                return None
        return self._description

    @property
    def location(self) -> str:
        """Return the path (expanded once loaded)."""
        if self._expanded is None:
            return " + ".join(str(sub) for sub in self._location)
        return self._expanded


class PythonLaunchDescriptionSource(LaunchDescriptionSource):
    """A Python launch file."""

    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(None, launch_file_path, "interpreted python launch file")

    def _load(self, location: str) -> LaunchDescription:
        return load_python_launch_file(location)


class FrontendLaunchDescriptionSource(LaunchDescriptionSource):
    """An XML or YAML launch file."""

    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(None, launch_file_path, "interpreted frontend launch file")

    def _load(self, location: str) -> LaunchDescription:
        return load_frontend_launch_file(location)


class AnyLaunchDescriptionSource(LaunchDescriptionSource):
    """A launch file of any format."""

    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(None, launch_file_path, "interpreted launch file")

    def _load(self, location: str) -> LaunchDescription:
        return load_any_launch_file(location)
