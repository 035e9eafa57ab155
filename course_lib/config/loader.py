"""Load an instructor's YAML file into frozen dataclasses, naming file, line and key on errors.

Pure code (PyYAML only). A schema is a frozen dataclass whose fields are bool, int, float, str,
`Literal[...]`, nested dataclasses, `tuple[X, ...]`, fixed tuples or `X | None`; limits come
from `setting(...)` metadata and cross-field checks raise `SettingValueError` in `__post_init__`.
"""

from __future__ import annotations

import dataclasses
import difflib
import types
import typing
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, TypeVar, Union

import yaml

from ..core.errors import ConfigError
from ..core.paths import REPO_ROOT
from .yaml_syntax import syntax_problem

__all__ = [
    "SettingValueError",
    "check_file",
    "check_text",
    "describe_limits",
    "display_path",
    "load_settings",
    "parse_settings",
    "setting",
]

if TYPE_CHECKING:
    from _typeshed import DataclassInstance

T = TypeVar("T", bound="DataclassInstance")  # a schema: a dataclass
_NONE = type(None)


class SettingValueError(ValueError):
    """Raised by a schema's `__post_init__` to reject a value; names the field."""

    def __init__(self, key: str, problem: str, hint: str = "") -> None:
        super().__init__(f"{key}: {problem}")
        self.key = key
        self.problem = problem
        self.hint = hint


def setting(default: Any = dataclasses.MISSING, *, help: str = "", **limits: Any) -> Any:
    """Declare a schema field with a help text and limits (gt, ge, lt, le, min_len, max_len)."""
    meta = {"help": help, **limits}
    if isinstance(default, (list, dict)):
        raise TypeError("use a tuple for a sequence default")
    return dataclasses.field(default=default, metadata=meta)


def display_path(path: str | Path) -> str:
    try:
        return str(Path(path).resolve().relative_to(REPO_ROOT))
    except ValueError:
        return str(path)


class _Broken(Exception):
    """A mapping held a fault (already recorded): its dataclass cannot be built."""


class _Converter:
    """Walk a composed YAML node tree against a schema, recording every fault it finds."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.problems: list[ConfigError] = []
        self._constructor = yaml.SafeLoader("")

    def fail(self, node: yaml.Node | None, key: str, problem: str, hint: str) -> ConfigError:
        line = node.start_mark.line + 1 if node is not None else None
        return ConfigError(self.source, line, key or "(top level)", problem, hint)

    def scalar(self, node: yaml.Node) -> Any:
        return self._constructor.construct_object(node, deep=True)

    def convert(self, node: yaml.Node, hint_type: Any, key: str) -> Any:
        origin = typing.get_origin(hint_type)
        if origin in (Union, types.UnionType):
            options = [a for a in typing.get_args(hint_type) if a is not _NONE]
            if node.tag == "tag:yaml.org,2002:null":
                return None
            return self.convert(node, options[0], key)
        if isinstance(hint_type, type) and dataclasses.is_dataclass(hint_type):
            return self.dataclass(node, hint_type, key)
        if origin is tuple:
            return self.sequence(node, typing.get_args(hint_type), key)
        if origin is Literal:
            return self.choice(node, typing.get_args(hint_type), key)
        return self.plain(node, hint_type, key)

    def plain(self, node: yaml.Node, kind: type, key: str) -> Any:
        names = {bool: "true or false", int: "a whole number", float: "a number", str: "text"}
        value = self.scalar(node) if isinstance(node, yaml.ScalarNode) else node
        ok = isinstance(value, kind) and not (kind is int and isinstance(value, bool))
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            return float(value)
        if not ok:
            shown = value if isinstance(node, yaml.ScalarNode) else f"a {node.id}"
            raise self.fail(
                node,
                key,
                f"expected {names.get(kind, kind.__name__)}, got {shown!r}",
                f"write {names.get(kind, kind.__name__)} for `{key}`.",
            )
        return value

    def choice(self, node: yaml.Node, options: tuple[Any, ...], key: str) -> Any:
        value = self.scalar(node) if isinstance(node, yaml.ScalarNode) else None
        if value not in options:
            valid = ", ".join(repr(o) for o in options)
            raise self.fail(node, key, f"{value!r} is not one of {valid}", f"use one of {valid}.")
        return value

    def sequence(self, node: yaml.Node, args: tuple[Any, ...], key: str) -> tuple[Any, ...]:
        if not isinstance(node, yaml.SequenceNode):
            raise self.fail(node, key, "expected a list", f"write `{key}` as a YAML list [a, b].")
        items = node.value
        if len(args) == 2 and args[1] is Ellipsis:
            kinds = [args[0]] * len(items)
        else:
            kinds = list(args)
            if len(items) != len(kinds):
                raise self.fail(
                    node,
                    key,
                    f"expected {len(kinds)} values, got {len(items)}",
                    f"write exactly {len(kinds)} values for `{key}`.",
                )
        converted, broken = [], False
        for i, (item, kind) in enumerate(zip(items, kinds, strict=True)):
            try:
                converted.append(self.convert(item, kind, f"{key}[{i}]"))
            except ConfigError as err:
                self.problems.append(err)
                broken = True
            except _Broken:
                broken = True
        if broken:
            raise _Broken
        return tuple(converted)

    def dataclass(self, node: yaml.Node, schema: type[T], key: str) -> T:
        if not isinstance(node, yaml.MappingNode):
            raise self.fail(node, key, "expected a mapping of keys", "write `key: value` lines.")
        fields = {f.name: f for f in dataclasses.fields(schema)}
        hints = typing.get_type_hints(schema)
        values: dict[str, Any] = {}
        lines: dict[str, yaml.Node] = {}
        before = len(self.problems)
        seen: set[str] = set()
        for key_node, value_node in node.value:
            name = str(self.scalar(key_node))
            full = f"{key}.{name}" if key else name
            try:
                self.field(key_node, name, full, fields, seen)
                values[name] = self.convert(value_node, hints[name], full)
                self.check_limits(value_node, fields[name].metadata, values[name], full)
            except ConfigError as err:
                self.problems.append(err)
            except _Broken:
                pass
            lines[name] = key_node
            lines[f"{name}[]"] = value_node
        for name in [n for n, f in fields.items() if n not in seen and _required(f)]:
            full = f"{key}.{name}" if key else name
            self.problems.append(self.fail(node, full, "missing", f"add `{name}:` here."))
        if len(self.problems) > before:
            raise _Broken
        try:
            return schema(**values)
        except SettingValueError as err:
            full = f"{key}.{err.key}" if key else err.key
            raise self.fail(
                _error_node(err.key, lines, node), full, err.problem, err.hint
            ) from None

    def field(
        self, node: yaml.Node, name: str, full: str, fields: dict[str, Any], seen: set[str]
    ) -> None:
        """Refuse a key the schema does not know, or one given twice."""
        if name not in fields:
            close = difflib.get_close_matches(name, fields, n=1, cutoff=0.5)
            hint = f"did you mean `{close[0]}`? " if close else ""
            raise self.fail(
                node, full, "unknown key", f"{hint}valid keys here: {', '.join(fields)}."
            )
        if name in seen:
            raise self.fail(node, full, "key given twice", "keep one of the two lines.")
        seen.add(name)

    def check_limits(self, node: yaml.Node, meta: Any, value: Any, key: str) -> None:
        tests: dict[str, tuple[Callable[[Any, Any], bool], str]] = {
            "gt": (lambda v, b: v > b, "greater than"),
            "ge": (lambda v, b: v >= b, "at least"),
            "lt": (lambda v, b: v < b, "less than"),
            "le": (lambda v, b: v <= b, "at most"),
            "min_len": (lambda v, b: len(v) >= b, "of length at least"),
            "max_len": (lambda v, b: len(v) <= b, "of length at most"),
        }
        for name, (test, words) in tests.items():
            if name in meta and value is not None and not test(value, meta[name]):
                shown = len(value) if name.endswith("_len") else value
                allowed = describe_limits(meta)
                raise self.fail(
                    node,
                    key,
                    f"{shown!r} is out of range (allowed: {allowed})",
                    f"use a value {words} {meta[name]}.",
                )


def _error_node(key: str, lines: dict[str, yaml.Node], node: yaml.Node) -> yaml.Node:
    """Return the node a schema's error names: `key`'s line, or item i's line for `key[i]`."""
    name, _, index = key.partition("[")
    items = lines.get(f"{name}[]")
    if index.rstrip("]").isdigit() and isinstance(items, yaml.SequenceNode):
        position = int(index.rstrip("]"))
        if position < len(items.value):
            return items.value[position]
    return lines.get(key, lines.get(name, node))


def _required(field: dataclasses.Field[Any]) -> bool:
    return field.default is dataclasses.MISSING and field.default_factory is dataclasses.MISSING


def describe_limits(meta: Any) -> str:
    """Return a field's limits in words, e.g. "> 0 and <= 0.26" ("any" without limits)."""
    signs = {
        "gt": ">",
        "ge": ">=",
        "lt": "<",
        "le": "<=",
        "min_len": "items >=",
        "max_len": "items <=",
    }
    parts = [f"{sign} {meta[name]:g}" for name, sign in signs.items() if name in meta]
    return " and ".join(parts) or "any"


def _compose(text: str, source: str) -> yaml.Node | None:
    try:
        return yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as err:
        line, problem = syntax_problem(text, err)
        raise ConfigError(
            source,
            line,
            "(syntax)",
            f"not valid YAML: {problem}",
            "write `key: value` (a colon and a space after each key), keep the indentation "
            "of the lines around it, and close every [ with ].",
        ) from None


def check_text(
    text: str, schema: type[T], *, source: str = "<string>"
) -> tuple[T | None, list[ConfigError]]:
    """Parse YAML text into `schema`; return it (None when broken) and every problem found."""
    try:
        root = _compose(text, source)
    except ConfigError as err:
        return None, [err]
    if root is None:
        root = yaml.MappingNode("tag:yaml.org,2002:map", [])
    converter = _Converter(source)
    try:
        return converter.dataclass(root, schema, ""), []
    except ConfigError as err:  # the top level's own check (its __post_init__)
        return None, [*converter.problems, err]
    except _Broken:
        return None, converter.problems


def _first(problems: list[ConfigError]) -> ConfigError:
    """Return the first problem, its hint naming how many more there are."""
    first = problems[0]
    if len(problems) > 1:
        first.hint += f" ({len(problems) - 1} more: `make check-config` lists them all.)"
    return first


def parse_settings(text: str, schema: type[T], *, source: str = "<string>") -> T:
    """Parse YAML text into `schema`; raise ConfigError naming `source`, line and key."""
    value, problems = check_text(text, schema, source=source)
    if problems or value is None:
        raise _first(problems)
    return value


def check_file(path: str | Path, schema: type[T]) -> tuple[T | None, list[ConfigError]]:
    """Read the YAML file at `path` into `schema`; return it (None when broken) and problems.

    A missing, unreadable or empty file is a problem too: it names the file and how to get the
    shipped one back.
    """
    source = display_path(path)
    restore = f"get the course's file back with `git checkout {source}`"
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        return None, [ConfigError(source, None, "(file)", "is missing", f"{restore}.")]
    except OSError as err:
        return None, [
            ConfigError(source, None, "(file)", f"cannot be read: {err.strerror}", f"{restore}.")
        ]
    if not any(line.split("#", 1)[0].strip() for line in text.splitlines()):
        problem = "holds no settings (it is empty)"
        return None, [ConfigError(source, None, "(file)", problem, f"{restore}.")]
    return check_text(text, schema, source=source)


def load_settings(path: str | Path, schema: type[T]) -> T:
    """Read the YAML file at `path` into `schema`; raise ConfigError on any fault."""
    value, problems = check_file(path, schema)
    if problems or value is None:
        raise _first(problems)
    return value
