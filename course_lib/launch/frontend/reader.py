"""XML and YAML launch files: read entities, then build the same actions Python files use.

A tag is read by the `parse(entity, parser)` of the action class that exposes it
(`@expose_action("tag")`, launch/api/exposure.py); `PARSER` is what they read entities with.
"""

from __future__ import annotations

import shlex
import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import Any

from ...core.files.bounded_yaml import safe_load_bounded
from ..api import actions, event_actions, process  # noqa: F401  (they expose their tags)
from ..api.conditions import IfCondition, UnlessCondition
from ..api.event_actions import Shutdown
from ..api.exposure import frontend_actions
from ..api.substitution_syntax import parse_if_substitutions, parse_substitution
from ..core.description import LaunchDescription
from ..core.loading import (
    CourseUnavailableError,
    InvalidFrontendLaunchFileError,
    is_frontend_filename,
    register_frontend,
)
from ..core.real_names import REAL_FRONTEND_TAGS
from ..core.substitution import TextSubstitution
from ..ros import node  # noqa: F401  (launch_ros's actions expose their tags)

__all__ = ["PARSER", "load_frontend_file", "parse_action", "parse_substitution"]


def _coerce(value: str) -> Any:
    """Type an XML attribute as launch_xml does: int, float, bool, else text."""
    for cast in (int, float):
        try:
            return cast(value)
        except ValueError:
            pass
    return {"true": True, "false": False}.get(value, value)


class Entity:
    """One XML element or YAML mapping, read the same way."""

    def __init__(
        self, type_name: str, attrs: dict[str, Any], children: list[Entity], typed: bool
    ) -> None:
        self.type_name = type_name
        self._attrs = attrs
        self._children = children
        self._typed = typed  # YAML values already carry types

    @property
    def children(self) -> list[Entity]:
        """Return the nested entities, in order."""
        return list(self._children)

    def get_attr(self, name: str, *, data_type: Any = str, optional: bool = False) -> Any:
        """Return an attribute, typed; `data_type=list` returns nested entities of that tag."""
        if data_type is list:
            found = [c for c in self._children if c.type_name == name]
            if name in self._attrs and isinstance(self._attrs[name], list):
                found += [_yaml_entity(name, item) for item in self._attrs[name]]
            if not found and not optional:
                raise AttributeError(
                    f"Attribute '{name}' of type 'List[Entity]' not found in Entity "
                    f"'{self.type_name}'"
                )
            return found or None
        if name not in self._attrs:
            if optional:
                return None
            raise AttributeError(
                f"Attribute '{name}' of type '{data_type}' not found in Entity '{self.type_name}'"
            )
        value = self._attrs[name]
        if data_type is None:
            return value if self._typed else _coerce(value)
        if data_type is bool and isinstance(value, str):
            return {"true": True, "false": False}.get(value.lower(), value)
        return value if self._typed or data_type is str else data_type(value)


def _xml_entity(element: ET.Element) -> Entity:
    return Entity(element.tag, dict(element.attrib), [_xml_entity(e) for e in element], False)


def _yaml_entity(type_name: str, body: Any) -> Entity:
    if isinstance(body, list):  # `launch:` and `group: children:` hold lists of actions
        return Entity(type_name, {}, [_yaml_child(item) for item in body], True)
    body = dict(body or {})
    children = [_yaml_child(item) for item in body.pop("children", [])]
    return Entity(type_name, body, children, True)


def _yaml_child(item: Any) -> Entity:
    if not isinstance(item, dict) or len(item) != 1:
        raise RuntimeError(f"Expected a mapping with one key (the action), got: {item!r}")
    ((type_name, body),) = item.items()
    return _yaml_entity(type_name, body)


def _load_entity(path: str) -> Entity:
    errors: list[Exception] = []
    loaders: list[Callable[[], Entity]] = [
        lambda: _xml_entity(ET.parse(path).getroot()),
        lambda: _yaml_root(path),
    ]
    if any(path.endswith("." + ext) for ext in ("yaml", "yml")):
        loaders.reverse()
    for loader in loaders:
        try:
            return loader()
        except Exception as exc:
            errors.append(exc)
    extension = path.rsplit(".", 1)[-1] if is_frontend_filename(path) else ""
    raise InvalidFrontendLaunchFileError(extension, likely_errors=errors)


def _yaml_root(path: str) -> Entity:
    with open(path) as handle:  # bounded: a few KB of nested aliases would fill the memory
        tree = safe_load_bounded(handle, name=path)
    if len(tree) != 1:
        raise RuntimeError("Expected only one root")
    ((type_name, body),) = tree.items()
    return _yaml_entity(type_name, body)


def load_frontend_file(path: str) -> LaunchDescription:
    """Parse an XML or YAML launch file into a LaunchDescription."""
    root = _load_entity(path)
    if root.type_name != "launch":
        raise RuntimeError("Expected 'launch' as root tag")
    return LaunchDescription([parse_action(child) for child in root.children])


def _subs(entity: Entity, name: str, optional: bool = True) -> Any:
    value = entity.get_attr(name, optional=optional)
    return None if value is None else parse_substitution(str(value))


def _condition(entity: Entity) -> dict[str, Any]:
    if_ = entity.get_attr("if", optional=True)
    unless = entity.get_attr("unless", optional=True)
    if if_ is not None:
        return {"condition": IfCondition(parse_substitution(str(if_)))}
    if unless is not None:
        return {"condition": UnlessCondition(parse_substitution(str(unless)))}
    return {}


def _process_kwargs(entity: Entity) -> dict[str, Any]:
    kwargs: dict[str, Any] = _condition(entity)
    for key, attr in (
        ("output", "output"),
        ("cwd", "cwd"),
        ("prefix", "launch-prefix"),
        ("sigterm_timeout", "sigterm_timeout"),
        ("sigkill_timeout", "sigkill_timeout"),
        ("respawn", "respawn"),
    ):
        value = _subs(entity, attr)
        if value is not None:
            kwargs[key] = value
    tty = entity.get_attr("emulate_tty", data_type=bool, optional=True)
    if tty is not None:
        kwargs["emulate_tty"] = tty
    delay = entity.get_attr("respawn_delay", optional=True)
    if delay is not None:
        kwargs["respawn_delay"] = float(delay)
    on_exit = entity.get_attr("on_exit", optional=True)
    if on_exit is not None:
        if on_exit != "shutdown":
            raise ValueError(
                f"Attribute on_exit of Entity node expected to be shutdown but got `{on_exit}`"
                "Other on_exit actions not yet supported"
            )
        kwargs["on_exit"] = [Shutdown()]
    env = entity.get_attr("env", data_type=list, optional=True) or []
    if env:
        kwargs["additional_env"] = {
            e.get_attr("name"): parse_substitution(str(e.get_attr("value"))) for e in env
        }
    return kwargs


def _cmdline(text: Any) -> list[Any]:
    """Split a command line into arguments, keeping `$(...)` inside the argument it is in."""
    args: list[list[Any]] = []
    current: list[Any] = []

    def close() -> None:
        nonlocal current
        if current:
            args.append(current)
            current = []

    for sub in parse_substitution(str(text)):
        if not isinstance(sub, TextSubstitution):
            current.append(sub)
            continue
        if sub.text[:1].isspace():
            close()
        try:
            tokens = shlex.split(sub.text)
        except ValueError:  # a quote closed after a substitution: split on spaces only
            tokens = sub.text.split()
        for index, token in enumerate(tokens):
            current.append(TextSubstitution(text=token))
            if index < len(tokens) - 1:
                close()
        if not tokens or sub.text[-1:].isspace():
            close()
    close()
    return args


class _Parser:
    """What an exposed action's `parse(entity, parser)` reads its entity with."""

    subs = staticmethod(_subs)
    condition = staticmethod(_condition)
    process_kwargs = staticmethod(_process_kwargs)
    command_line = staticmethod(_cmdline)
    parse_substitution = staticmethod(parse_substitution)
    parse_if_substitutions = staticmethod(parse_if_substitutions)

    @staticmethod
    def parse_action(entity: Entity) -> Any:
        """Build the action of a nested entity (a group's, a timer's)."""
        return parse_action(entity)


PARSER = _Parser()


def parse_action(entity: Entity) -> Any:
    """Build the action for one entity, with the `parse` of the class exposing its tag."""
    parsers = frontend_actions()
    if entity.type_name not in parsers:
        if entity.type_name in REAL_FRONTEND_TAGS:
            raise CourseUnavailableError(
                f"'{entity.type_name}' (a launch file tag) is not available in this course; "
                f"it has: {', '.join(sorted(parsers))}"
            )
        raise RuntimeError(f"Unrecognized entity of the type: {entity.type_name}")
    return parsers[entity.type_name](entity, PARSER)


register_frontend(load_frontend_file)
