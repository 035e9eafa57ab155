"""The `launch`/`launch_ros` modules that launch files import, installed only while in use.

Nothing named `launch` or `launch_ros` is ever put on the import path: the modules below
are built in memory and placed in `sys.modules` inside `launch_modules()` only, then the
previous entries (a real ROS 2 install's, if any) are put back. A name or module of real
launch that the course lacks raises `CourseUnavailableError`, one line naming it.
"""

from __future__ import annotations

import difflib
import sys
import threading
import types
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from importlib.machinery import ModuleSpec
from typing import Any

from ..api import (  # noqa: F401  (importing them exposes their classes)
    actions,
    conditions,
    event_actions,
    logic_substitutions,
    process,
    substitutions,
)
from ..api.exposure import exposed_modules
from ..core import (
    context,
    description,
    entity,
    event,
    event_handlers,
    events,
    loading,
    substitution,
)
from ..core.loading import CourseUnavailableError
from ..core.real_names import REAL_NAMES
from ..frontend import reader as frontend  # noqa: F401  (registers the XML/YAML loader)
from ..ros import node, parameters  # noqa: F401  (importing them exposes their classes)

__all__ = ["MODULE_NAMES", "launch_modules"]

_lock = threading.RLock()
_depth = 0
_saved: dict[str, Any] = {}
_ROOTS = ("launch", "launch_ros", "launch_xml", "launch_yaml")


def _pick(module: types.ModuleType, names: str) -> dict[str, Any]:
    return {name: getattr(module, name) for name in names.split()}


def _sources() -> dict[str, Any]:
    return {
        **_pick(
            description,
            "AnyLaunchDescriptionSource FrontendLaunchDescriptionSource "
            "PythonLaunchDescriptionSource",
        ),
        **_pick(
            loading,
            "InvalidFrontendLaunchFileError InvalidLaunchFileError InvalidPythonLaunchFileError",
        ),
    }


# The modules launch files may import, in the order a misplaced name's hint looks through them.
MODULE_NAMES = (
    "launch",
    "launch.actions",
    "launch.substitutions",
    "launch.substitutions.substitution_failure",
    "launch.launch_description_sources",
    "launch.conditions",
    "launch.event_handler",
    "launch.event_handlers",
    "launch.events",
    "launch.events.process",
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


def _core_names() -> dict[str, dict[str, Any]]:
    """Names from launch/core, which sits below the exposure registry (so lists them here)."""
    return {
        "launch": {
            **_pick(context, "LaunchContext"),
            **_pick(description, "LaunchDescription LaunchDescriptionSource"),
            **_pick(entity, "Action Condition LaunchDescriptionEntity"),
            **_pick(event, "Event"),
            **_pick(event_handlers, "EventHandler"),
            **_pick(loading, "InvalidLaunchFileError"),
            **_pick(substitution, "Substitution"),
            "SomeSubstitutionsType": Any,
            "SomeEntitiesType": Any,
        },
        "launch.substitutions": _pick(substitution, "SubstitutionFailure TextSubstitution"),
        "launch.substitutions.substitution_failure": _pick(substitution, "SubstitutionFailure"),
        "launch.launch_description_sources": _sources(),
        "launch.event_handler": _pick(event_handlers, "EventHandler"),
        "launch.event_handlers": _pick(
            event_handlers,
            "OnExecutionComplete OnProcessExit OnProcessIO OnProcessStart OnShutdown",
        ),
        "launch.events": _pick(events, "ExecutionComplete Shutdown"),
        "launch.events.process": _pick(
            events,
            "ProcessExited ProcessIO ProcessStarted ProcessStderr ProcessStdout "
            "RunningProcessEvent",
        ),
        "launch.launch_context": _pick(context, "LaunchContext"),
        "launch.launch_description": _pick(description, "LaunchDescription"),
        "launch.some_substitutions_type": {"SomeSubstitutionsType": Any},
        "launch.utilities": _pick(
            substitution, "normalize_to_list_of_substitutions perform_substitutions"
        ),
        "launch_xml.launch_description_sources": {
            "XMLLaunchDescriptionSource": description.FrontendLaunchDescriptionSource
        },
        "launch_yaml.launch_description_sources": {
            "YAMLLaunchDescriptionSource": description.FrontendLaunchDescriptionSource
        },
    }


def _table() -> dict[str, dict[str, Any]]:
    """Return module -> names: launch/core's, then what the classes expose themselves."""
    core, exposed = _core_names(), exposed_modules()
    unknown = sorted(set(exposed) - set(MODULE_NAMES))
    if unknown:
        raise RuntimeError(f"exposed in modules the shim does not build: {unknown}")
    return {name: {**core.get(name, {}), **exposed.get(name, {})} for name in MODULE_NAMES}


def _unavailable(what: str, module: str, names: Sequence[str] = ()) -> CourseUnavailableError:
    has = f"; '{module}' here has: {', '.join(names)}" if names else ""
    return CourseUnavailableError(f"{what} is not available in this course{has}")


def _missing_name(
    module: str, names: Sequence[str], table: dict[str, dict[str, Any]]
) -> Callable[[str], Any]:
    def __getattr__(name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        if name in REAL_NAMES.get(module, ()):
            raise _unavailable(f"'{name}' of '{module}'", module, names)
        elsewhere = [other for other, attrs in table.items() if name in attrs]
        close = difflib.get_close_matches(name, names, n=1)
        hint = f". Did you mean: '{close[0]}'?" if close else ""
        if elsewhere:
            hint = f". It is in '{elsewhere[0]}'"
        raise ImportError(f"cannot import name '{name}' from '{module}' (unknown location){hint}")

    return __getattr__


class _MissingModules:
    """Meta path finder: `import launch.frontend` (absent here) fails with one clear line."""

    def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> ModuleSpec | None:
        if fullname.split(".")[0] in _ROOTS and fullname not in sys.modules:
            raise _unavailable(f"module '{fullname}'", fullname.rsplit(".", 1)[0])
        return None


_finder = _MissingModules()


def _build() -> dict[str, types.ModuleType]:
    modules: dict[str, types.ModuleType] = {}
    table = _table()
    for name, attrs in table.items():
        module = types.ModuleType(name, f"The course's stand-in for `{name}`.")
        module.__dict__.update(attrs)
        module.__path__ = []  # a package: submodules resolve through sys.modules
        modules[name] = module
    for name, module in modules.items():  # `import launch` then `launch.actions.X`
        parent, _, child = name.rpartition(".")
        if parent:
            setattr(modules[parent], child, module)
    for name, module in modules.items():
        public = sorted(n for n in vars(module) if not n.startswith("_"))
        module.__getattr__ = _missing_name(name, public, table)  # type: ignore[method-assign]
    return modules


@contextmanager
def launch_modules() -> Iterator[None]:
    """Make `import launch`/`launch_ros` resolve to the course's versions, in this block."""
    global _depth
    with _lock:
        if _depth == 0:
            for name, module in _build().items():
                _saved[name] = sys.modules.get(name)
                sys.modules[name] = module
            sys.meta_path.insert(0, _finder)
        _depth += 1
    try:
        yield
    finally:
        with _lock:
            _depth -= 1
            if _depth == 0:
                sys.meta_path.remove(_finder)
                for name, previous in _saved.items():
                    if previous is None:
                        sys.modules.pop(name, None)
                    else:
                        sys.modules[name] = previous
                _saved.clear()
