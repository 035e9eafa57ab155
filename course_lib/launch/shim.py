"""The `launch`/`launch_ros` modules that launch files import, installed only while in use.

Nothing named `launch` or `launch_ros` is ever put on the import path: the modules below
are built in memory and placed in `sys.modules` inside `launch_modules()` only, then the
previous entries (a real ROS 2 install's, if any) are put back.
"""

from __future__ import annotations

import sys
import threading
import types
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

__all__ = ["MODULE_NAMES", "launch_modules"]

_lock = threading.RLock()
_depth = 0
_saved: dict[str, Any] = {}


def _table() -> dict[str, dict[str, Any]]:
    from . import actions, context, description, node, parameters, process, substitutions
    from .frontend import FrontendLaunchDescriptionSource

    subs = {name: getattr(substitutions, name) for name in substitutions.__all__}
    launch_actions = {name: getattr(actions, name) for name in actions.__all__}
    launch_actions["ExecuteProcess"] = process.ExecuteProcess
    sources = {
        "AnyLaunchDescriptionSource": description.AnyLaunchDescriptionSource,
        "FrontendLaunchDescriptionSource": FrontendLaunchDescriptionSource,
        "PythonLaunchDescriptionSource": description.PythonLaunchDescriptionSource,
    }
    params = {
        name: getattr(parameters, name)
        for name in ("Parameter", "ParameterFile", "ParameterValue")
    }
    ros_subs = {
        name: subs[name]
        for name in ("ExecutableInPackage", "FindPackagePrefix", "FindPackageShare")
    }
    top = {
        "LaunchContext": context.LaunchContext,
        "LaunchDescription": description.LaunchDescription,
        "LaunchDescriptionEntity": description.LaunchDescriptionEntity,
        "LaunchDescriptionSource": description.LaunchDescriptionSource,
        "Action": description.Action,
        "Condition": description.Condition,
        "Substitution": substitutions.Substitution,
        "SomeSubstitutionsType": Any,
    }
    return {
        "launch": top,
        "launch.actions": launch_actions,
        "launch.substitutions": subs,
        "launch.substitutions.substitution_failure": {
            "SubstitutionFailure": substitutions.SubstitutionFailure
        },
        "launch.launch_description_sources": sources,
        "launch.conditions": {
            "IfCondition": description.IfCondition,
            "UnlessCondition": description.UnlessCondition,
        },
        "launch.launch_context": {"LaunchContext": context.LaunchContext},
        "launch.launch_description": {"LaunchDescription": description.LaunchDescription},
        "launch.some_substitutions_type": {"SomeSubstitutionsType": Any},
        "launch.utilities": {
            "perform_substitutions": substitutions.perform_substitutions,
            "normalize_to_list_of_substitutions": substitutions.normalize_to_list_of_substitutions,
        },
        "launch_xml": {},
        "launch_xml.launch_description_sources": {
            "XMLLaunchDescriptionSource": FrontendLaunchDescriptionSource
        },
        "launch_yaml": {},
        "launch_yaml.launch_description_sources": {
            "YAMLLaunchDescriptionSource": FrontendLaunchDescriptionSource
        },
        "launch_ros": {},
        "launch_ros.actions": {
            name: getattr(node, name)
            for name in ("Node", "PushRosNamespace", "SetParameter", "SetRemap")
        },
        "launch_ros.substitutions": ros_subs,
        "launch_ros.parameter_descriptions": params,
        "launch_ros.descriptions": params,
    }


MODULE_NAMES = (
    "launch",
    "launch.actions",
    "launch.substitutions",
    "launch.substitutions.substitution_failure",
    "launch.launch_description_sources",
    "launch.conditions",
    "launch.launch_context",
    "launch.launch_description",
    "launch.some_substitutions_type",
    "launch.utilities",
    "launch_xml",
    "launch_xml.launch_description_sources",
    "launch_yaml",
    "launch_yaml.launch_description_sources",
    "launch_ros",
    "launch_ros.actions",
    "launch_ros.substitutions",
    "launch_ros.parameter_descriptions",
    "launch_ros.descriptions",
)


def _build() -> dict[str, types.ModuleType]:
    modules: dict[str, types.ModuleType] = {}
    for name, attrs in _table().items():
        module = types.ModuleType(name, f"The course's stand-in for `{name}`.")
        module.__dict__.update(attrs)
        module.__path__ = []  # a package: submodules resolve through sys.modules
        modules[name] = module
    for name, module in modules.items():  # `import launch` then `launch.actions.X`
        parent, _, child = name.rpartition(".")
        if parent:
            setattr(modules[parent], child, module)
    return modules


@contextmanager
def launch_modules() -> Iterator[None]:
    """Make `import launch`/`launch_ros` resolve to the course's versions, in this block."""
    global _depth
    with _lock:
        if _depth == 0:
            modules = _build()
            for name, module in modules.items():
                _saved[name] = sys.modules.get(name)
                sys.modules[name] = module
        _depth += 1
    try:
        yield
    finally:
        with _lock:
            _depth -= 1
            if _depth == 0:
                for name, previous in _saved.items():
                    if previous is None:
                        sys.modules.pop(name, None)
                    else:
                        sys.modules[name] = previous
                _saved.clear()
