"""The `$(name arg ...)` substitution language of XML and YAML launch files."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..core.loading import CourseUnavailableError
from ..core.real_names import REAL_FRONTEND_SUBSTITUTIONS
from ..core.substitution import Substitution, TextSubstitution
from .logic_substitutions import (
    AllSubstitution,
    AndSubstitution,
    AnySubstitution,
    IfElseSubstitution,
    NotSubstitution,
    OrSubstitution,
)
from .substitutions import (
    Command,
    EnvironmentVariable,
    EqualsSubstitution,
    ExecutableInPackage,
    FindExecutable,
    FindPackagePrefix,
    FindPackageShare,
    LaunchConfiguration,
    NotEqualsSubstitution,
    PythonExpression,
    ThisLaunchFile,
    ThisLaunchFileDir,
)

__all__ = ["parse_if_substitutions", "parse_substitution"]

Args = list[list[Substitution]]


def _count(name: str, args: Args, low: int, high: int) -> None:
    if not low <= len(args) <= high:
        many = (
            f"{low} or {high} arguments"
            if low != high
            else (f"{low} argument" if low == 1 else f"{low} arguments")
        )
        raise TypeError(f"{name} substitution expects {many}")


def _var(args: Args) -> Substitution:
    _count("var", args, 1, 2)
    return LaunchConfiguration(args[0], default=args[1] if len(args) > 1 else None)


def _env(args: Args) -> Substitution:
    _count("env", args, 1, 2)
    return EnvironmentVariable(args[0], default_value=args[1] if len(args) > 1 else None)


def _optenv(args: Args) -> Substitution:
    _count("optenv", args, 1, 2)
    return EnvironmentVariable(args[0], default_value=args[1] if len(args) > 1 else "")


def _package(cls: type) -> Callable[[Args], Substitution]:
    def make(args: Args) -> Substitution:
        if len(args) != 1:
            raise AttributeError("find package substitutions expect 1 argument")
        return cls(args[0])

    return make


def _exec_in_pkg(args: Args) -> Substitution:
    if len(args) != 2:
        raise AttributeError("exec-in-package substitution expects 2 arguments")
    return ExecutableInPackage(executable=args[0], package=args[1])


def _no_args(cls: type, name: str) -> Callable[[Args], Substitution]:
    def make(args: Args) -> Substitution:
        if args:
            raise TypeError(f"{name} substitution doesn't expect arguments")
        return cls()

    return make


def _eval(args: Args) -> Substitution:
    _count("eval", args, 1, 2)
    return PythonExpression(args[0])


def _command(args: Args) -> Substitution:
    if not 1 <= len(args) <= 2:
        raise ValueError("command substitution expects 1 or 2 arguments")
    return Command(args[0], on_stderr=args[1] if len(args) > 1 else "fail")


def _find_exec(args: Args) -> Substitution:
    if len(args) != 1:
        raise AttributeError("find-exec substitution expects 1 argument")
    return FindExecutable(name=args[0])


def _fixed(cls: type, name: str, count: int) -> Callable[[Args], Substitution]:
    def make(args: Args) -> Substitution:
        if len(args) != count:
            raise TypeError(f"{name} substitution expects {count} argument{'s' * (count > 1)}")
        return cls(*args)

    return make


def _if(args: Args) -> Substitution:
    if not 2 <= len(args) <= 3:
        raise TypeError("if substitution expects from 2 or 3 arguments")
    return IfElseSubstitution(*args)


_MAKERS: dict[str, Callable[[Args], Substitution]] = {
    "var": _var,
    "env": _env,
    "optenv": _optenv,
    "find-pkg-share": _package(FindPackageShare),
    "find-pkg-prefix": _package(FindPackagePrefix),
    "exec-in-pkg": _exec_in_pkg,
    "dirname": _no_args(ThisLaunchFileDir, "dirname"),
    "filename": _no_args(ThisLaunchFile, "filename"),
    "eval": _eval,
    "command": _command,
    "find-exec": _find_exec,
    "not": _fixed(NotSubstitution, "not", 1),
    "and": _fixed(AndSubstitution, "and", 2),
    "or": _fixed(OrSubstitution, "and", 2),  # launch's own message says "and" here
    "any": lambda args: AnySubstitution(*args),
    "all": lambda args: AllSubstitution(*args),
    "if": _if,
    "equals": _fixed(EqualsSubstitution, "and", 2),  # (sic, as launch says)
    "not-equals": _fixed(NotEqualsSubstitution, "not-equals", 2),
}


def _fragment(text: str, i: int, stop: Callable[[str], bool]) -> tuple[list[Substitution], int]:
    """Parse text and nested `$(...)` until `stop(char)`; return (substitutions, index)."""
    out: list[Substitution] = []
    buf: list[str] = []
    while i < len(text) and not stop(text[i]):
        if text.startswith("\\$", i):
            buf.append("$")
            i += 2
        elif text.startswith("$(", i):
            if buf:
                out.append(TextSubstitution(text="".join(buf)))
                buf = []
            sub, i = _substitution(text, i + 2)
            out.append(sub)
        else:
            buf.append(text[i])
            i += 1
    if buf:
        out.append(TextSubstitution(text="".join(buf)))
    return out, i


def _substitution(text: str, i: int) -> tuple[Substitution, int]:
    start = i
    while i < len(text) and not text[i].isspace() and text[i] != ")":
        i += 1
    name = text[start:i]
    args: Args = []
    while True:
        while i < len(text) and text[i].isspace():
            i += 1
        if i >= len(text):
            raise ValueError(f"unterminated substitution '$({text[start:]}'")
        if text[i] == ")":
            break
        if text[i] in "'\"":
            quote = text[i]
            arg, i = _fragment(text, i + 1, lambda c, q=quote: c == q)
            i += 1
        else:
            arg, i = _fragment(text, i, lambda c: c.isspace() or c == ")")
        args.append(arg)
    if name not in _MAKERS:
        if name in REAL_FRONTEND_SUBSTITUTIONS:
            raise CourseUnavailableError(
                f"'$({name} ...)' is not available in this course; it has: "
                f"{', '.join(sorted(_MAKERS))}"
            )
        raise RuntimeError(f"Unknown substitution: {name}")
    return _MAKERS[name](args), i + 1


def parse_substitution(text: str) -> list[Substitution]:
    """Parse `text` with `$(...)` substitutions into a list of substitutions."""
    subs, _ = _fragment(text, 0, lambda c: False)
    return subs or [TextSubstitution(text="")]


def parse_if_substitutions(value: Any) -> Any:
    """Parse strings (and lists of strings) for substitutions; keep other values."""
    if isinstance(value, str):
        return parse_substitution(value)
    if isinstance(value, list):
        return [parse_if_substitutions(v) for v in value]
    return value
