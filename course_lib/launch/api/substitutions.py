"""Substitutions of the launch API (`launch.substitutions`, `launch_ros.substitutions`)."""

from __future__ import annotations

import importlib
import math
import os
import shlex
import shutil
import subprocess
from collections.abc import Iterable
from typing import Any

from ..core.substitution import (
    Substitution,
    SubstitutionFailure,
    TextSubstitution,
    as_text,
    describe_all,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "Command",
    "EnvironmentVariable",
    "EqualsSubstitution",
    "ExecutableInPackage",
    "FindExecutable",
    "FindPackagePrefix",
    "FindPackageShare",
    "LaunchConfiguration",
    "LocalSubstitution",
    "NotEqualsSubstitution",
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


class LocalSubstitution(Substitution):
    """A value from the context's locals, e.g. `ros_specific_arguments['name']`."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        self.expression = expression
        self.description = description

    def perform(self, context: Any) -> str:
        # launch evaluates `context.locals.<expression>` (e.g. `event.reason`).
        return eval("context.locals." + self.expression, {"context": context})

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
        return f"LaunchConfig({describe_all(self.variable_name)})"


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
        return f"EnvVar({describe_all(self.name)})"


class PathJoinSubstitution(Substitution):
    """Join path parts with the OS separator."""

    def __init__(self, substitutions: Iterable[Any]) -> None:
        self.substitutions = [normalize_to_list_of_substitutions(s) for s in substitutions]

    def perform(self, context: Any) -> str:
        return os.path.join(*(perform_substitutions(context, s) for s in self.substitutions))

    def describe(self) -> str:
        return f"PathJoin('{' + '.join(describe_all(s) for s in self.substitutions)}')"


def _note_code_run(context: Any, what: str) -> None:
    """Remember that evaluating ran code (a dry run says so)."""
    ran = getattr(context, "code_run", None)
    if ran is not None:
        ran.append(what)


class PythonExpression(Substitution):
    """Evaluate a Python expression (with `math` available), as real launch does."""

    def __init__(self, expression: Any, python_modules: Any = ("math",)) -> None:
        self.expression = normalize_to_list_of_substitutions(expression)
        self.python_modules = [normalize_to_list_of_substitutions(m) for m in python_modules]

    def perform(self, context: Any) -> str:
        names = [perform_substitutions(context, m) for m in self.python_modules]
        scope: dict[str, Any] = {}
        for module in (importlib.import_module(name) for name in names):
            if module is math:  # launch lets expressions use math's names bare
                scope.update(vars(module))
            scope[module.__name__] = module
        expression = perform_substitutions(context, self.expression)
        _note_code_run(context, f"a Python expression: {expression}")
        return str(eval(expression, {}, scope))

    def describe(self) -> str:
        return f"PythonExpr({describe_all(self.expression)})"


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
        return f"{type(self).__name__}(pkg={describe_all(self.package)})"


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
        return f"ExecInPkg(pkg={describe_all(self.package)}, exec={describe_all(self.executable)})"


class FindExecutable(Substitution):
    """The full path of an executable found on the PATH."""

    def __init__(self, *, name: Any) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def perform(self, context: Any) -> str:
        name = perform_substitutions(context, self.name)
        found = shutil.which(name, path=context.environment.get("PATH"))
        if found is None:
            raise SubstitutionFailure(f"executable '{name}' not found on the PATH")
        return found

    def describe(self) -> str:
        return f"FindExec({describe_all(self.name)})"


_ON_STDERR = ("fail", "ignore", "warn", "capture")


class Command(Substitution):
    """The standard output of a command (split like a shell would, without a shell)."""

    def __init__(self, command: Any, *, on_stderr: Any = "fail") -> None:
        self.command = normalize_to_list_of_substitutions(command)
        self.on_stderr = normalize_to_list_of_substitutions(on_stderr)

    def perform(self, context: Any) -> str:
        text = perform_substitutions(context, self.command)
        on_stderr = perform_substitutions(context, self.on_stderr)
        if on_stderr not in _ON_STDERR:
            raise SubstitutionFailure(
                "expected 'on_stderr' to be one of: 'fail', 'ignore', 'warn' or 'capture'"
            )
        stderr = subprocess.STDOUT if on_stderr == "capture" else subprocess.PIPE
        _note_code_run(context, f"a command: {text}")
        try:
            result = subprocess.run(
                shlex.split(text), stdout=subprocess.PIPE, stderr=stderr, text=True, check=False
            )
        except FileNotFoundError as exc:
            raise SubstitutionFailure(f"file not found: {exc}") from None
        if result.returncode != 0:
            message = f"executed command failed. Command: {text}"
            if result.stderr:
                message += f"\nCaptured stderr output: {result.stderr}"
            raise SubstitutionFailure(message)
        if result.stderr:
            message = (
                f"executed command showed stderr output. Command: {text}\n"
                f"Captured stderr output:\n{result.stderr}"
            )
            if on_stderr == "fail":
                raise SubstitutionFailure(message)
            if on_stderr == "warn":
                context.log("launch", "WARNING", message)
        return result.stdout

    def describe(self) -> str:
        return f"Command({describe_all(self.command)})"


def _is_bool(text: str) -> bool:
    return text.lower() in ("true", "false", "1", "0")


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


class EqualsSubstitution(Substitution):
    """`true` when both sides are equal (as booleans, as numbers, else as text)."""

    def __init__(self, left: Any, right: Any) -> None:
        self.left = normalize_to_list_of_substitutions(_as_text(left))
        self.right = normalize_to_list_of_substitutions(_as_text(right))

    def _equal(self, context: Any) -> bool:
        left = perform_substitutions(context, self.left)
        right = perform_substitutions(context, self.right)
        if _is_bool(left) and _is_bool(right):
            return (left.lower() in ("true", "1")) == (right.lower() in ("true", "1"))
        if _is_float(left) and _is_float(right):
            return math.isclose(float(left), float(right))
        return left == right

    def perform(self, context: Any) -> str:
        return str(self._equal(context)).lower()

    def describe(self) -> str:
        return f"EqualsSubstitution({describe_all(self.left)} {describe_all(self.right)})"


class NotEqualsSubstitution(EqualsSubstitution):
    """`true` when the sides differ."""

    def perform(self, context: Any) -> str:
        return str(not self._equal(context)).lower()

    def describe(self) -> str:
        return f"NotEqualsSubstitution({describe_all(self.left)} {describe_all(self.right)})"


def _as_text(value: Any) -> Any:
    if value is None:
        return ""
    return str(value).lower() if isinstance(value, bool) else as_text(value)
