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
    describe_all,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)
from .exposure import Args, expect_arguments, expose, expose_substitution

__all__ = [
    "Command",
    "EnvironmentVariable",
    "ExecutableInPackage",
    "FindExecutable",
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


@expose("launch.substitutions")
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


@expose_substitution("var")
class LaunchConfiguration(Substitution):
    """The value of a launch configuration (a launch argument or `let`)."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(var name [default])`."""
        expect_arguments(name, args, 1, 2)
        return cls(args[0], default=args[1] if len(args) > 1 else None)

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


@expose_substitution("env", "optenv")
class EnvironmentVariable(Substitution):
    """The value of an environment variable of the launch."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(env NAME [default])`; `$(optenv NAME [default])` defaults to ''."""
        expect_arguments(name, args, 1, 2)
        default = args[1] if len(args) > 1 else ("" if name == "optenv" else None)
        return cls(args[0], default_value=default)

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


@expose("launch.substitutions")
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


@expose_substitution("eval")
class PythonExpression(Substitution):
    """Evaluate a Python expression (with `math` available), as real launch does."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(eval expression)` (a second argument, the modules, is accepted and unused)."""
        expect_arguments(name, args, 1, 2)
        return cls(args[0])

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


def _without_arguments(cls: type[Substitution], name: str, args: Args) -> Substitution:
    if args:
        raise TypeError(f"{name} substitution doesn't expect arguments")
    return cls()


@expose_substitution("dirname")
class ThisLaunchFileDir(Substitution):
    """The folder of the launch file being evaluated."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(dirname)`."""
        return _without_arguments(cls, name, args)

    def perform(self, context: Any) -> str:
        if "current_launch_file_directory" not in context.locals:
            raise SubstitutionFailure(
                "ThisLaunchFileDir used outside of a launch file (in a script)"
            )
        return context.locals["current_launch_file_directory"]

    def describe(self) -> str:
        return "ThisLaunchFileDir()"


@expose_substitution("filename")
class ThisLaunchFile(Substitution):
    """The path of the launch file being evaluated."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(filename)`."""
        return _without_arguments(cls, name, args)

    def perform(self, context: Any) -> str:
        if "current_launch_file_path" not in context.locals:
            raise SubstitutionFailure("ThisLaunchFile used outside of a launch file (in a script)")
        return context.locals["current_launch_file_path"]

    def describe(self) -> str:
        return "ThisLaunchFile()"


@expose_substitution("find-pkg-prefix", module="launch_ros.substitutions")
class FindPackagePrefix(Substitution):
    """The install prefix of a package, from the ament index."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(find-pkg-prefix package)` (and `find-pkg-share`)."""
        if len(args) != 1:
            raise AttributeError("find package substitutions expect 1 argument")
        return cls(args[0])

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


@expose_substitution("find-pkg-share", module="launch_ros.substitutions")
class FindPackageShare(FindPackagePrefix):
    """The share folder of a package, from the ament index."""

    def find(self, package: str) -> str:
        from ament_index_python.packages import get_package_share_directory

        return get_package_share_directory(package)


@expose_substitution("exec-in-pkg", module="launch_ros.substitutions")
class ExecutableInPackage(FindPackagePrefix):
    """The path of an executable in `<prefix>/lib/<package>`."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(exec-in-pkg executable package)`."""
        if len(args) != 2:
            raise AttributeError("exec-in-package substitution expects 2 arguments")
        return cls(executable=args[0], package=args[1])

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


@expose_substitution("find-exec")
class FindExecutable(Substitution):
    """The full path of an executable found on the PATH."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(find-exec name)`."""
        expect_arguments(name, args, 1, error=AttributeError)
        return cls(name=args[0])

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


@expose_substitution("command")
class Command(Substitution):
    """The standard output of a command (split like a shell would, without a shell)."""

    @classmethod
    def parse(cls, name: str, args: Args) -> Substitution:
        """`$(command 'cmd args' [on_stderr])`."""
        expect_arguments(name, args, 1, 2, error=ValueError)
        return cls(args[0], on_stderr=args[1] if len(args) > 1 else "fail")

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
