"""One way to offer an action or substitution: exposed beside its class, read by the shim."""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import pytest

import course_lib.launch.api as api_package
import course_lib.launch.ros as ros_package
from course_lib.launch.api import exposure
from course_lib.launch.api.substitution_syntax import parse_substitution
from course_lib.launch.core.entity import Action
from course_lib.launch.core.substitution import Substitution
from course_lib.launch.runtime import shim

# What launch files find in the course: ROS 2 Jazzy's names that the course offers.
SUBSTITUTIONS = {
    "launch.substitutions": {
        "AllSubstitution", "AndSubstitution", "AnySubstitution", "Command",
        "EnvironmentVariable", "EqualsSubstitution", "FindExecutable", "IfElseSubstitution",
        "LaunchConfiguration", "LocalSubstitution", "NotEqualsSubstitution", "NotSubstitution",
        "OrSubstitution", "PathJoinSubstitution", "PythonExpression", "SubstitutionFailure",
        "TextSubstitution", "ThisLaunchFile", "ThisLaunchFileDir",
    },
    "launch_ros.substitutions": {"ExecutableInPackage", "FindPackagePrefix", "FindPackageShare"},
}  # fmt: skip
ACTIONS = {
    "launch.actions": {
        "DeclareLaunchArgument", "EmitEvent", "ExecuteProcess", "GroupAction",
        "IncludeLaunchDescription", "LogInfo", "OpaqueFunction", "RegisterEventHandler",
        "SetEnvironmentVariable", "SetLaunchConfiguration", "Shutdown", "TimerAction",
        "UnregisterEventHandler",
    },
    "launch_ros.actions": {
        "Node", "PushROSNamespace", "PushRosNamespace", "SetParameter", "SetParametersFromFile",
        "SetRemap",
    },
}  # fmt: skip
FRONTEND_SUBSTITUTIONS = {
    "all", "and", "any", "command", "dirname", "env", "equals", "eval", "exec-in-pkg",
    "filename", "find-exec", "find-pkg-prefix", "find-pkg-share", "if", "not", "not-equals",
    "optenv", "or", "var",
}  # fmt: skip
FRONTEND_TAGS = {
    "arg", "executable", "group", "include", "let", "log", "node", "push-ros-namespace",
    "push_ros_namespace", "set_env", "set_parameter", "set_parameters_from_file", "set_remap",
    "shutdown", "timer",
}  # fmt: skip


def _shim() -> dict[str, dict[str, object]]:
    return shim._table()


def _classes_of(package: object, base: type) -> list[type]:
    """Every public subclass of `base` defined in the modules of `package`."""
    found = []
    for info in pkgutil.walk_packages(package.__path__, package.__name__ + "."):  # type: ignore[attr-defined]
        module = importlib.import_module(info.name)
        for name, value in vars(module).items():
            if (
                inspect.isclass(value)
                and issubclass(value, base)
                and value.__module__ == module.__name__
                and not name.startswith("_")
            ):
                found.append(value)
    return found


@pytest.mark.parametrize("module", sorted({**SUBSTITUTIONS, **ACTIONS}))
def test_the_shim_offers_what_the_course_has(module: str) -> None:
    expected = {**SUBSTITUTIONS, **ACTIONS}[module]
    assert set(_shim()[module]) == expected


def test_the_frontend_offers_what_the_course_has() -> None:
    assert set(exposure.frontend_substitutions()) == FRONTEND_SUBSTITUTIONS
    assert set(exposure.frontend_actions()) == FRONTEND_TAGS


@pytest.mark.parametrize("name", sorted(exposure.frontend_classes()))
def test_every_frontend_name_builds_a_class_the_shim_offers(name: str) -> None:
    cls = exposure.frontend_classes()[name]
    offered = [module for module, names in _shim().items() if names.get(cls.__name__) is cls]
    assert offered, f"{name} builds {cls.__name__}, which no shim module offers"


@pytest.mark.parametrize("package", [api_package, ros_package], ids=["api", "ros"])
def test_no_action_or_substitution_class_is_left_unexposed(package: object) -> None:
    """A class of api/ or ros/ that launch files could use is in a shim module; one with a
    frontend `parse` is reachable by a `$(name)` or a tag (forgetting the decorator fails)."""
    shim_classes = {id(v) for names in _shim().values() for v in names.values()}
    frontend = set(map(id, exposure.frontend_classes().values()))
    for cls in _classes_of(package, Action) + _classes_of(package, Substitution):
        assert id(cls) in shim_classes, f"{cls.__qualname__} is exposed in no shim module"
        if "parse" in vars(cls):
            assert id(cls) in frontend, f"{cls.__qualname__}.parse is reached by no tag or $()"


@pytest.mark.parametrize(
    ("text", "error", "message"),
    [
        ("$(var)", TypeError, "var substitution expects 1 or 2 arguments"),
        ("$(optenv A B C)", TypeError, "optenv substitution expects 1 or 2 arguments"),
        ("$(find-pkg-share)", AttributeError, "find package substitutions expect 1 argument"),
        ("$(exec-in-pkg a)", AttributeError, "exec-in-package substitution expects 2 arguments"),
        ("$(dirname x)", TypeError, "dirname substitution doesn't expect arguments"),
        ("$(command)", ValueError, "command substitution expects 1 or 2 arguments"),
        ("$(find-exec)", AttributeError, "find-exec substitution expects 1 argument"),
        ("$(not)", TypeError, "not substitution expects 1 argument"),
        ("$(or a)", TypeError, "and substitution expects 2 arguments"),  # (sic) as launch says
        ("$(equals a)", TypeError, "and substitution expects 2 arguments"),  # (sic)
        ("$(not-equals a)", TypeError, "not-equals substitution expects 2 arguments"),
        ("$(if a)", TypeError, "if substitution expects from 2 or 3 arguments"),
    ],
)
def test_a_substitutions_arguments_are_checked_in_launchs_words(
    text: str, error: type, message: str
) -> None:
    with pytest.raises(error) as raised:
        parse_substitution(text)
    assert str(raised.value) == message


def test_optenv_defaults_to_empty_and_share_builds_its_own_class() -> None:
    (optenv,) = parse_substitution("$(optenv NO_SUCH_VARIABLE)")
    assert optenv.default_value is not None
    (share,) = parse_substitution("$(find-pkg-share p)")
    assert type(share).__name__ == "FindPackageShare"


@pytest.fixture
def empty_registry(monkeypatch: pytest.MonkeyPatch) -> None:
    for table in ("_modules", "_substitutions", "_actions", "_classes"):
        monkeypatch.setattr(exposure, table, {})


@pytest.mark.usefixtures("empty_registry")
def test_two_things_under_one_name_are_refused_but_a_reimport_is_not() -> None:
    class First:
        @classmethod
        def parse(cls, name: str, args: list) -> object:
            return cls()

    class Second(First):
        pass

    exposure.expose_substitution("var")(First)
    exposure.expose_substitution("var")(First)  # a re-imported module: the same class
    with pytest.raises(exposure.ExposureError, match=r"'\$\(var \.\.\.\)' is exposed twice"):
        exposure.expose_substitution("var")(Second)
    with pytest.raises(exposure.ExposureError, match=r"substitutions\.First' is exposed twice"):
        exposure.expose("launch.substitutions", name="First")(Second)
    assert exposure.exposed_modules() == {"launch.substitutions": {"First": First}}
