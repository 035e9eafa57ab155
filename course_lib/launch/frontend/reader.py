"""XML and YAML launch files: read entities, then build the same actions Python files use."""

from __future__ import annotations

import shlex
import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import Any

from ...core.bounded_yaml import safe_load_bounded
from ..api import actions as la
from ..api.conditions import IfCondition, UnlessCondition
from ..api.event_actions import Shutdown
from ..api.process import ExecuteProcess
from ..api.substitution_syntax import parse_if_substitutions, parse_substitution
from ..core.description import AnyLaunchDescriptionSource, LaunchDescription
from ..core.loading import (
    CourseUnavailableError,
    InvalidFrontendLaunchFileError,
    is_frontend_filename,
    register_frontend,
)
from ..core.real_names import REAL_FRONTEND_TAGS
from ..core.substitution import TextSubstitution
from ..ros.node import Node, PushRosNamespace, SetParameter, SetParametersFromFile, SetRemap
from ..ros.parameters import ParameterFile, ParameterValue

__all__ = ["load_frontend_file", "parse_action", "parse_substitution"]


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


def _params(entity: Entity) -> list[Any]:
    result: list[Any] = []
    for param in entity.get_attr("param", data_type=list, optional=True) or []:
        source = param.get_attr("from", optional=True)
        name = param.get_attr("name", optional=True)
        if source is not None and name is not None:
            raise RuntimeError("name and from attributes are mutually exclusive")
        if source is not None:
            result.append(ParameterFile(parse_substitution(str(source))))
        elif name is not None:
            value = param.get_attr("value", data_type=None, optional=True)
            if value is None:
                raise RuntimeError("either a value attribute or nested params are needed")
            result.append({name: ParameterValue(parse_if_substitutions(value))})
        else:
            raise ValueError("param Entity should have name or from attribute")
    return result


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


def _node(entity: Entity) -> Node:
    kwargs = _process_kwargs(entity)
    kwargs["executable"] = _subs(entity, "exec", optional=False)
    for key, attr in (
        ("package", "pkg"),
        ("name", "name"),
        ("namespace", "namespace"),
        ("exec_name", "exec_name"),
    ):
        value = _subs(entity, attr)
        if value is not None:
            kwargs[key] = value
    for key, attr in (("arguments", "args"), ("ros_arguments", "ros_args")):
        value = entity.get_attr(attr, optional=True)
        if value is not None:
            kwargs[key] = _cmdline(value)
    remaps = entity.get_attr("remap", data_type=list, optional=True) or []
    if remaps:
        kwargs["remappings"] = [(_subs(r, "from", False), _subs(r, "to", False)) for r in remaps]
    params = _params(entity)
    if params:
        kwargs["parameters"] = params
    return Node(**kwargs)


def _include(entity: Entity) -> la.IncludeLaunchDescription:
    args = entity.get_attr("arg", data_type=list, optional=True) or []
    return la.IncludeLaunchDescription(
        AnyLaunchDescriptionSource(_subs(entity, "file", optional=False)),
        launch_arguments=[(_subs(a, "name", False), _subs(a, "value", False)) for a in args],
        **_condition(entity),
    )


def _arg(entity: Entity) -> la.DeclareLaunchArgument:
    default = entity.get_attr("default", optional=True)
    return la.DeclareLaunchArgument(
        str(entity.get_attr("name")),
        default_value=None if default is None else parse_substitution(str(default)),
        description=entity.get_attr("description", optional=True),
        **_condition(entity),
    )


_PARSERS: dict[str, Callable[[Entity], Any]] = {
    "node": _node,
    "include": _include,
    "arg": _arg,
    "let": lambda e: la.SetLaunchConfiguration(
        _subs(e, "name", False), _subs(e, "value", False), **_condition(e)
    ),
    "executable": lambda e: ExecuteProcess(
        cmd=_cmdline(e.get_attr("cmd")), name=_subs(e, "name"), **_process_kwargs(e)
    ),
    "group": lambda e: la.GroupAction(
        [parse_action(c) for c in e.children if c.type_name != "env"],
        scoped=e.get_attr("scoped", data_type=bool, optional=True) is not False,
        **_condition(e),
    ),
    "timer": lambda e: la.TimerAction(
        period=_subs(e, "period", False),
        actions=[parse_action(c) for c in e.children],
        **_condition(e),
    ),
    "log": lambda e: la.LogInfo(msg=_subs(e, "message", False), **_condition(e)),
    "set_env": lambda e: la.SetEnvironmentVariable(
        _subs(e, "name", False), _subs(e, "value", False), **_condition(e)
    ),
    "push-ros-namespace": lambda e: PushRosNamespace(_subs(e, "namespace", False)),
    "push_ros_namespace": lambda e: PushRosNamespace(_subs(e, "namespace", False)),
    "set_parameter": lambda e: SetParameter(
        _subs(e, "name", False), _subs(e, "value", False), **_condition(e)
    ),
    "set_parameters_from_file": lambda e: SetParametersFromFile(
        _subs(e, "filename", False), **_condition(e)
    ),
    "set_remap": lambda e: SetRemap(
        _subs(e, "from", False), _subs(e, "to", False), **_condition(e)
    ),
    "shutdown": lambda e: Shutdown(
        reason=e.get_attr("reason", optional=True) or "reason not given"
    ),
}


def parse_action(entity: Entity) -> Any:
    """Build the action for one entity."""
    if entity.type_name not in _PARSERS:
        if entity.type_name in REAL_FRONTEND_TAGS:
            raise CourseUnavailableError(
                f"'{entity.type_name}' (a launch file tag) is not available in this course; "
                f"it has: {', '.join(sorted(_PARSERS))}"
            )
        raise RuntimeError(f"Unrecognized entity of the type: {entity.type_name}")
    return _PARSERS[entity.type_name](entity)


register_frontend(load_frontend_file)
