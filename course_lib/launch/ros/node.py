"""`launch_ros.actions.Node` and friends: a ROS node as a process with ROS arguments."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

import yaml

from ...core import param_journal
from ..api.exposure import expose_action
from ..api.process import ExecuteProcess, ProcessSpec
from ..api.substitution_syntax import parse_if_substitutions, parse_substitution
from ..api.substitutions import ExecutableInPackage
from ..core.entity import Action
from ..core.substitution import normalize_to_list_of_substitutions, perform_substitutions
from .parameters import (
    Parameter,
    ParameterFile,
    ParameterValue,
    evaluate_parameter_dict,
    normalize_parameters,
    write_params_file,
)

__all__ = [
    "Node",
    "ParameterSource",
    "PushRosNamespace",
    "SetParameter",
    "SetParametersFromFile",
    "SetRemap",
]

UNSPECIFIED_NAME = "<node_name_unspecified>"
UNSPECIFIED_NAMESPACE = "<node_namespace_unspecified>"


def prefix_namespace(base: str | None, ns: str | None) -> str | None:
    """Return `ns` prefixed with `base` when `ns` is relative (trailing `/` stripped)."""
    if base is None and ns is None:
        return None
    if ns is None:
        combined = base
    elif not base or ns.startswith("/"):
        combined = ns
    else:
        combined = f"{base.rstrip('/')}/{ns}"
    return combined if combined == "/" else combined.rstrip("/")  # type: ignore[union-attr]


def make_namespace_absolute(ns: str | None) -> str | None:
    """Return `ns` with a leading `/`."""
    if ns is None:
        return None
    return ns if ns.startswith("/") else "/" + ns


@dataclass
class ParameterSource:
    """One `parameters=[...]` item of a node, resolved: where values come from."""

    kind: str  # 'dict' | 'file' | 'rule' | 'global'
    path: str | None = None  # the params file the node gets (temporary for dicts)
    values: dict[str, Any] = field(default_factory=dict)


def _frontend_parameters(entity: Any) -> list[Any]:
    """Return the `<param name= value=/>` and `<param from=/>` children of a `<node>`."""
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


@expose_action("node", module="launch_ros.actions")
class Node(ExecuteProcess):
    """Run a ROS node: `<exe> [args] --ros-args -r __node:=... --params-file ... -r a:=b`."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<node pkg= exec= name= namespace= args= ros_args=>` with param/remap/env children."""
        kwargs = parser.process_kwargs(entity)
        kwargs["executable"] = parser.subs(entity, "exec", optional=False)
        for key, attr in (
            ("package", "pkg"),
            ("name", "name"),
            ("namespace", "namespace"),
            ("exec_name", "exec_name"),
        ):
            value = parser.subs(entity, attr)
            if value is not None:
                kwargs[key] = value
        for key, attr in (("arguments", "args"), ("ros_arguments", "ros_args")):
            value = entity.get_attr(attr, optional=True)
            if value is not None:
                kwargs[key] = parser.command_line(value)
        remaps = entity.get_attr("remap", data_type=list, optional=True) or []
        if remaps:
            pairs = [(parser.subs(r, "from", False), parser.subs(r, "to", False)) for r in remaps]
            kwargs["remappings"] = pairs
        params = _frontend_parameters(entity)
        if params:
            kwargs["parameters"] = params
        return cls(**kwargs)

    def __init__(
        self,
        *,
        executable: Any,
        package: Any = None,
        name: Any = None,
        namespace: Any = None,
        exec_name: Any = None,
        parameters: Any = None,
        remappings: Any = None,
        ros_arguments: Any = None,
        arguments: Any = None,
        **kwargs: Any,
    ) -> None:
        cmd: list[Any] = [
            ExecutableInPackage(executable=executable, package=package)
            if package is not None
            else executable
        ]
        cmd += list(arguments or [])
        cmd += ["--ros-args", *ros_arguments] if ros_arguments else []
        kwargs["name"] = exec_name
        super().__init__(cmd=cmd, **kwargs)
        self.node_package = package
        self.node_executable = executable
        self._name = name
        self._namespace = namespace
        self._parameters = [] if parameters is None else normalize_parameters(parameters)
        self._remappings = [
            (normalize_to_list_of_substitutions(a), normalize_to_list_of_substitutions(b))
            for a, b in (remappings or [])
        ]
        self.node_name: str | None = None
        self.parameter_sources: list[ParameterSource] = []
        self.remappings: list[tuple[str, str]] = []

    def is_node_name_fully_specified(self) -> bool:
        """Return whether both the name and the namespace are known."""
        return all(
            x not in (self.node_name or "") for x in (UNSPECIFIED_NAME, UNSPECIFIED_NAMESPACE)
        )

    def _ros_arguments(self, context: Any) -> list[str]:
        args = ["--ros-args"]
        name = UNSPECIFIED_NAME
        if self._name is not None:
            name = perform_substitutions(context, normalize_to_list_of_substitutions(self._name))
            args += ["-r", f"__node:={name}"]
        ns = (
            None
            if self._namespace is None
            else perform_substitutions(
                context, normalize_to_list_of_substitutions(self._namespace)
            )
        )
        ns = make_namespace_absolute(
            prefix_namespace(context.launch_configurations.get("ros_namespace"), ns)
        )
        if ns is not None:
            args += ["-r", f"__ns:={ns}"]
        self.node_name = prefix_namespace(ns or UNSPECIFIED_NAMESPACE, name)
        args += self._parameter_arguments(context)
        self.remappings = list(context.launch_configurations.get("ros_remaps", []))
        self.remappings += [
            (perform_substitutions(context, a), perform_substitutions(context, b))
            for a, b in self._remappings
        ]
        for src, dst in self.remappings:
            args += ["-r", f"{src}:={dst}"]
        return args

    def _parameter_arguments(self, context: Any) -> list[str]:
        write = context.runtime is not None
        self.parameter_sources = []
        args: list[str] = []
        for item in context.launch_configurations.get("global_params", []):
            if isinstance(item, tuple):
                name, value = item
                args += ["-p", f"{name}:={value}"]
                self.parameter_sources.append(ParameterSource("global", None, {name: value}))
            else:
                path = os.path.abspath(item)
                args += ["--params-file", path]
                self.parameter_sources.append(ParameterSource("file", path))
        for item in self._parameters:
            if isinstance(item, dict):
                values = evaluate_parameter_dict(context, item)
                known = self.node_name and self.is_node_name_fully_specified()
                key = self.node_name if known and self.node_name else "/**"
                path = write_params_file(key, values) if write else None
                self.parameter_sources.append(ParameterSource("dict", path, values))
                args += ["--params-file", path or "<temporary params file>"]
            elif isinstance(item, Parameter):
                name, value = item.evaluate(context)
                self.parameter_sources.append(ParameterSource("rule", None, {name: value}))
                args += ["-p", f"{name}:={yaml.dump(value)}"]
            else:
                path = str(item.evaluate(context))
                if not os.path.isfile(path):
                    context.log(
                        "launch_ros.actions.node",
                        "WARNING",
                        f"Parameter file path is not a file: {path}",
                    )
                    continue
                self.parameter_sources.append(ParameterSource("file", path))
                args += ["--params-file", path]
        return args

    def prepare(self, context: Any) -> ProcessSpec:
        spec = super().prepare(context)
        spec.cmd += self._ros_arguments(context)
        spec.extra["node_name"] = self.node_name
        return spec

    def execute(self, context: Any) -> None:
        super().execute(context)
        if context.runtime is not None and self.spec is not None:
            self._journal_start(context)
        if self.is_node_name_fully_specified() and self.spec is not None:
            context.node_names.append(self.node_name)
            count = context.node_names.count(self.node_name)
            if count > 1:
                context.log(
                    self.spec.name,
                    "WARNING",
                    f"there are now at least {count} nodes with the name "
                    f"{self.node_name} created within this launch context",
                )

    def _journal_name(self) -> str | None:
        """Return the node's full name as it will run (no namespace given: the root one)."""
        name = (self.node_name or "").replace(UNSPECIFIED_NAMESPACE + "/", "/")
        return None if UNSPECIFIED_NAME in name or not name else name.replace("//", "/")

    def _journal_start(self, context: Any) -> None:
        """Tell the lab's parameter journal where this node's start-up overrides come from."""
        assert self.spec is not None
        param_journal.append(
            self.spec.env.get("ROS_DOMAIN_ID") or os.environ.get("ROS_DOMAIN_ID"),
            {
                "t": "start",
                "door": "launch",
                "launch_file": str(getattr(context.locals, "current_launch_file_path", "")),
                "exe": os.path.basename(str(self.spec.cmd[0])),
                "node": self._journal_name(),
                "sources": [
                    {"kind": s.kind, "path": s.path, "values": s.values}
                    for s in self.parameter_sources
                ],
                "cwd": self.spec.cwd or os.getcwd(),
            },
        )


@expose_action(
    "push-ros-namespace",
    "push_ros_namespace",
    module="launch_ros.actions",
    aliases=("PushROSNamespace",),
)
class PushRosNamespace(Action):
    """Prefix the namespace of the nodes that follow (in this scope)."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<push-ros-namespace namespace=/>`."""
        return cls(parser.subs(entity, "namespace", False))

    def __init__(self, namespace: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.namespace = normalize_to_list_of_substitutions(namespace)

    def execute(self, context: Any) -> None:
        ns = perform_substitutions(context, self.namespace)
        base = context.launch_configurations.get("ros_namespace")
        context.launch_configurations["ros_namespace"] = make_namespace_absolute(
            prefix_namespace(base, ns)
        )


def _extend_global(context: Any, key: str, items: list[Any]) -> None:
    # launch_ros extends the list in place: a group scopes only a list it created itself.
    found = context.launch_configurations.get(key, [])
    found.extend(items)
    context.launch_configurations[key] = found


@expose_action("set_parameter", module="launch_ros.actions")
class SetParameter(Action):
    """Give every node that follows (in this scope) a parameter."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<set_parameter name= value=/>`."""
        name, value = parser.subs(entity, "name", False), parser.subs(entity, "value", False)
        return cls(name, value, **parser.condition(entity))

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.parameter = Parameter(name, value)

    def execute(self, context: Any) -> None:
        _extend_global(context, "global_params", [self.parameter.evaluate(context)])


@expose_action("set_parameters_from_file", module="launch_ros.actions")
class SetParametersFromFile(Action):
    """Give every node that follows (in this scope) the parameters of a params file."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<set_parameters_from_file filename=/>`."""
        return cls(parser.subs(entity, "filename", False), **parser.condition(entity))

    def __init__(self, filename: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.filename = normalize_to_list_of_substitutions(filename)

    def execute(self, context: Any) -> None:
        _extend_global(context, "global_params", [perform_substitutions(context, self.filename)])


@expose_action("set_remap", module="launch_ros.actions")
class SetRemap(Action):
    """Give every node that follows (in this scope) a remapping."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<set_remap from= to=/>`."""
        src, dst = parser.subs(entity, "from", False), parser.subs(entity, "to", False)
        return cls(src, dst, **parser.condition(entity))

    def __init__(self, src: Any, dst: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.src = normalize_to_list_of_substitutions(src)
        self.dst = normalize_to_list_of_substitutions(dst)

    def execute(self, context: Any) -> None:
        pair = (perform_substitutions(context, self.src), perform_substitutions(context, self.dst))
        _extend_global(context, "ros_remaps", [pair])
