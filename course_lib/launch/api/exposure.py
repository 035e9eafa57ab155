"""The one way to offer a launch action or substitution: a declaration beside its class.

As ros2/launch's `@expose_action`/`@expose_substitution`, a class says where launch files find
it: its name in a `launch`/`launch_ros` module (the shim builds those modules from here), its
`$(name ...)` in XML/YAML substitutions and its XML/YAML tag (the frontend reads those from
here)::

    @expose_substitution("var")
    class LaunchConfiguration(Substitution):
        @classmethod
        def parse(cls, name, args): ...  # the `$(var ...)` arguments, parsed into substitutions

    @expose_action("log")
    class LogInfo(Action):
        @classmethod
        def parse(cls, entity, parser): ...  # an XML element or YAML mapping

The registry is filled by the modules that define the classes (api/, ros/) and read by the
layers above them (frontend/, runtime/): none of them lists a name again.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

__all__ = [
    "ExposureError",
    "expect_arguments",
    "expose",
    "expose_action",
    "expose_substitution",
    "exposed_modules",
    "frontend_actions",
    "frontend_classes",
    "frontend_substitutions",
]

T = TypeVar("T")
Args = list[list[Any]]  # a `$(name arg ...)`'s arguments, each a list of substitutions
SubstitutionMaker = Callable[[Args], Any]
ActionParser = Callable[[Any, Any], Any]  # (entity, parser) -> action

_modules: dict[str, dict[str, Any]] = {}
_substitutions: dict[str, SubstitutionMaker] = {}
_actions: dict[str, ActionParser] = {}
_classes: dict[str, type] = {}  # "$(name)" or "<tag>" -> the class it builds


class ExposureError(ValueError):
    """Two different things exposed under one name."""


def _keep(table: dict[str, Any], key: str, value: Any, what: str) -> None:
    """Record a name once; the same thing again (a re-imported module) changes nothing."""
    known = table.get(key)
    if known is not None and known is not value and _origin(known) != _origin(value):
        raise ExposureError(f"{what} is exposed twice: {_origin(known)} and {_origin(value)}")
    table[key] = value


def _origin(value: Any) -> str:
    target = getattr(value, "__self__", value)  # a bound classmethod: its class
    return f"{getattr(target, '__module__', '?')}.{getattr(target, '__qualname__', target)}"


def expose(*modules: str, name: str | None = None) -> Callable[[T], T]:
    """Offer the decorated class or function as `<module>.<name>` in each of `modules`."""

    def register(thing: T) -> T:
        attribute = name or thing.__name__  # type: ignore[attr-defined]
        for module in modules:
            _keep(_modules.setdefault(module, {}), attribute, thing, f"'{module}.{attribute}'")
        return thing

    return register


def expose_substitution(
    *frontend_names: str, module: str = "launch.substitutions"
) -> Callable[[type[T]], type[T]]:
    """Offer a substitution class in `module` and as `$(name ...)` for each frontend name.

    The class's `parse(name, args)` classmethod builds it from a `$(name ...)`'s arguments.
    """

    def register(cls: type[T]) -> type[T]:
        for frontend_name in frontend_names:
            maker = _maker(cls, frontend_name)
            _keep(_substitutions, frontend_name, maker, f"'$({frontend_name} ...)'")
            _classes[f"$({frontend_name})"] = cls
        return expose(module)(cls)

    return register


def _maker(cls: type, frontend_name: str) -> SubstitutionMaker:
    parse = cls.parse  # type: ignore[attr-defined]

    def make(args: Args) -> Any:
        return parse(frontend_name, args)

    make.__module__, make.__qualname__ = cls.__module__, cls.__qualname__
    return make


def expose_action(
    *tags: str,
    module: str = "launch.actions",
    parse: ActionParser | None = None,
    aliases: tuple[str, ...] = (),
) -> Callable[[type[T]], type[T]]:
    """Offer an action class in `module` (also as `aliases`) and as XML/YAML `tags`.

    Each tag is read by the class's `parse(entity, parser)` classmethod, or by `parse` when the
    class is defined in a lower layer (launch/core) and cannot carry it.
    """

    def register(cls: type[T]) -> type[T]:
        reader = parse or getattr(cls, "parse", None)
        if tags and reader is None:
            raise ExposureError(f"{cls.__qualname__} has XML/YAML tags {tags} but no parse")
        for tag in tags:
            _keep(_actions, tag, reader, f"the launch file tag '{tag}'")
            _classes[f"<{tag}>"] = cls
        for name in (cls.__name__, *aliases):
            expose(module, name=name)(cls)
        return cls

    return register


def expect_arguments(
    name: str, args: Args, low: int, high: int | None = None, *, error: type = TypeError
) -> None:
    """Raise `error` as launch does when a `$(name ...)` has the wrong number of arguments."""
    high = low if high is None else high
    if low <= len(args) <= high:
        return
    if low != high:
        many = f"{low} or {high} arguments"
    else:
        many = f"{low} argument" if low == 1 else f"{low} arguments"
    raise error(f"{name} substitution expects {many}")


def exposed_modules() -> dict[str, dict[str, Any]]:
    """Return module name -> {name: class or function} of everything exposed so far."""
    return {module: dict(names) for module, names in _modules.items()}


def frontend_substitutions() -> dict[str, SubstitutionMaker]:
    """Return `$(name ...)` -> maker(args) of every exposed substitution."""
    return dict(_substitutions)


def frontend_actions() -> dict[str, ActionParser]:
    """Return XML/YAML tag -> parse(entity, parser) of every exposed action."""
    return dict(_actions)


def frontend_classes() -> dict[str, type]:
    """Return `$(name)` and `<tag>` -> the class each builds (for tests and documentation)."""
    return dict(_classes)
