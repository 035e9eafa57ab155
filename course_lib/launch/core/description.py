"""Launch descriptions and where they come from (launch file sources)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from .context import LaunchContext
from .entity import LaunchDescriptionEntity
from .launch_argument import DeclareLaunchArgument
from .loading import load_any_launch_file, load_frontend_launch_file, load_python_launch_file
from .substitution import normalize_to_list_of_substitutions, perform_substitutions

__all__ = [
    "AnyLaunchDescriptionSource",
    "FrontendLaunchDescriptionSource",
    "LaunchDescription",
    "LaunchDescriptionSource",
    "PythonLaunchDescriptionSource",
    "load_any_launch_file",
]


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
        found: list[Any] = []
        names: set[str] = set()

        def walk(entities: list[Any], conditional: bool) -> None:
            for entity in entities:
                cond = conditional or getattr(entity, "condition", None) is not None
                if isinstance(entity, DeclareLaunchArgument) and entity.name not in names:
                    entity._conditionally_included = cond
                    names.add(entity.name)
                    found.append(entity)
                walk(entity.describe_sub_entities(), cond)
                walk(entity.describe_conditional_sub_entities(), True)

        walk(self.entities, conditional_inclusion)
        return found


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
