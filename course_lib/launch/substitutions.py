"""Substitutions of the launch API (`launch.substitutions`, `launch_ros.substitutions`)."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

__all__ = [
    "EnvironmentVariable",
    "ExecutableInPackage",
    "FindPackagePrefix",
    "FindPackageShare",
    "LaunchConfiguration",
    "LocalSubstitution",
    "PathJoinSubstitution",
    "PythonExpression",
    "Substitution",
    "SubstitutionFailure",
    "TextSubstitution",
    "ThisLaunchFile",
    "ThisLaunchFileDir",
    "normalize_to_list_of_substitutions",
    "perform_substitutions",
]


class SubstitutionFailure(RuntimeError):
    """A substitution could not be performed (missing configuration, variable, ...)."""


class Substitution:
    """Base of every substitution: `perform(context)` returns text."""

    def perform(self, context: Any) -> str:
        """Return the text this substitution stands for."""
        raise NotImplementedError

    def describe(self) -> str:
        """Return a short description, as `--show-args` prints it."""
        return repr(self)

    def __str__(self) -> str:
        return self.describe()


def normalize_to_list_of_substitutions(value: Any) -> list[Substitution]:
    """Turn text, a substitution or an iterable of both into a list of substitutions."""
    if isinstance(value, str):
        return [TextSubstitution(text=value)]
    if isinstance(value, Substitution):
        return [value]
    if isinstance(value, os.PathLike):
        return [TextSubstitution(text=os.fspath(value))]
    if isinstance(value, Iterable):
        result: list[Substitution] = []
        for item in value:
            result.extend(normalize_to_list_of_substitutions(item))
        return result
    raise TypeError(
        f"value '{value}' is not a str, Substitution or iterable of them ({type(value)})"
    )


def perform_substitutions(context: Any, subs: Iterable[Substitution]) -> str:
    """Perform each substitution and join the texts."""
    return "".join(sub.perform(context) for sub in subs)


def _describe_all(subs: Iterable[Substitution]) -> str:
    return " + ".join(sub.describe() for sub in subs)


class TextSubstitution(Substitution):
    """Plain text."""

    def __init__(self, *, text: str) -> None:
        if not isinstance(text, str):
            raise TypeError(f"TextSubstitution expected Text object got '{type(text)}' instead.")
        self.text = text

    def perform(self, context: Any) -> str:
        return self.text

    def describe(self) -> str:
        return f"'{self.text}'"


class LocalSubstitution(Substitution):
    """A value from the context's locals, e.g. `ros_specific_arguments['name']`."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        self.expression = expression
        self.description = description

    def perform(self, context: Any) -> str:
        name, _, key = self.expression.partition("[")
        value = context.locals[name]
        return str(value[key.strip("]'\"")] if key else value)

    def describe(self) -> str:
        return self.description or f"LocalVar('{self.expression}')"


class LaunchConfiguration(Substitution):
    """The value of a launch configuration (a launch argument or `let`)."""

    def __init__(self, variable_name: Any, *, default: Any = None) -> None:
        self.variable_name = normalize_to_list_of_substitutions(variable_name)
        self.default = (
            None
            if default is None
            else normalize_to_list_of_substitutions(
                str(default) if isinstance(default, (int, float)) else default
            )
        )

    def perform(self, context: Any) -> str:
        name = perform_substitutions(context, self.variable_name)
        if name in context.launch_configurations:
            return context.launch_configurations[name]
        if self.default is None:
            raise SubstitutionFailure(f"launch configuration '{name}' does not exist")
        return perform_substitutions(context, self.default)

    def describe(self) -> str:
        return f"LaunchConfig({_describe_all(self.variable_name)})"


class EnvironmentVariable(Substitution):
    """The value of an environment variable of the launch."""

    def __init__(self, name: Any, *, default_value: Any = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.default_value = (
            None if default_value is None else normalize_to_list_of_substitutions(default_value)
        )

    def perform(self, context: Any) -> str:
        name = perform_substitutions(context, self.name)
        value = context.environment.get(name)
        if value is not None:
            return value
        if self.default_value is None:
            raise SubstitutionFailure(f"environment variable '{name}' does not exist")
        return perform_substitutions(context, self.default_value)

    def describe(self) -> str:
        return f"EnvVar({_describe_all(self.name)})"


class PathJoinSubstitution(Substitution):
    """Join path parts with the OS separator."""

    def __init__(self, substitutions: Iterable[Any]) -> None:
        self.substitutions = [normalize_to_list_of_substitutions(s) for s in substitutions]

    def perform(self, context: Any) -> str:
        return os.path.join(*(perform_substitutions(context, s) for s in self.substitutions))

    def describe(self) -> str:
        return f"PathJoin('{' + '.join(_describe_all(s) for s in self.substitutions)}')"


class PythonExpression(Substitution):
    """Evaluate a Python expression (with `math` available), as real launch does."""

    def __init__(self, expression: Any, python_modules: Any = ("math",)) -> None:
        self.expression = normalize_to_list_of_substitutions(expression)
        self.python_modules = [normalize_to_list_of_substitutions(m) for m in python_modules]

    def perform(self, context: Any) -> str:
        import importlib

        names = [perform_substitutions(context, m) for m in self.python_modules]
        scope = {name: importlib.import_module(name) for name in names}
        if "math" in scope:
            scope.update(vars(scope["math"]))
        return str(eval(perform_substitutions(context, self.expression), scope))

    def describe(self) -> str:
        return f"PythonExpr({_describe_all(self.expression)})"


class ThisLaunchFileDir(Substitution):
    """The folder of the launch file being evaluated."""

    def perform(self, context: Any) -> str:
        if "current_launch_file_directory" not in context.locals:
            raise SubstitutionFailure(
                "ThisLaunchFileDir used outside of a launch file (in a script)"
            )
        return context.locals["current_launch_file_directory"]

    def describe(self) -> str:
        return "ThisLaunchFileDir()"


class ThisLaunchFile(Substitution):
    """The path of the launch file being evaluated."""

    def perform(self, context: Any) -> str:
        if "current_launch_file_path" not in context.locals:
            raise SubstitutionFailure("ThisLaunchFile used outside of a launch file (in a script)")
        return context.locals["current_launch_file_path"]

    def describe(self) -> str:
        return "ThisLaunchFile()"


class FindPackagePrefix(Substitution):
    """The install prefix of a package, from the ament index."""

    def __init__(self, package: Any) -> None:
        self.package = normalize_to_list_of_substitutions(package)

    def find(self, package: str) -> str:
        """Return the folder for `package`."""
        from ament_index_python.packages import get_package_prefix

        return get_package_prefix(package)

    def perform(self, context: Any) -> str:
        return self.find(perform_substitutions(context, self.package))

    def describe(self) -> str:
        return f"{type(self).__name__}(pkg={_describe_all(self.package)})"


class FindPackageShare(FindPackagePrefix):
    """The share folder of a package, from the ament index."""

    def find(self, package: str) -> str:
        from ament_index_python.packages import get_package_share_directory

        return get_package_share_directory(package)


class ExecutableInPackage(FindPackagePrefix):
    """The path of an executable in `<prefix>/lib/<package>`."""

    def __init__(self, executable: Any, package: Any) -> None:
        super().__init__(package)
        self.executable = normalize_to_list_of_substitutions(executable)

    def perform(self, context: Any) -> str:
        import shutil

        executable = perform_substitutions(context, self.executable)
        package = perform_substitutions(context, self.package)
        prefix = self.find(package)
        libexec = os.path.join(prefix, "lib", package)
        if not os.path.exists(libexec):
            raise SubstitutionFailure(
                f"package '{package}' found at '{prefix}', but libexec directory "
                f"'{libexec}' does not exist"
            )
        found = shutil.which(executable, path=libexec)
        if found is None:
            raise SubstitutionFailure(
                f"executable '{executable}' not found on the libexec directory '{libexec}' "
            )
        return found

    def describe(self) -> str:
        return (
            f"ExecInPkg(pkg={_describe_all(self.package)}, exec={_describe_all(self.executable)})"
        )
