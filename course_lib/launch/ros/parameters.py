"""Node parameters as launch_ros takes them: dicts, files, single rules; params files."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import yaml

from ..api.exposure import expose
from ..api.substitution_syntax import parse_substitution
from ..core.substitution import (
    Substitution,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "Parameter",
    "ParameterFile",
    "ParameterValue",
    "evaluate_parameter_dict",
    "normalize_parameters",
    "write_params_file",
]

WRITTEN_FILES: list[str] = []  # temporary params files of this process, removed after launch


@expose("launch_ros.parameter_descriptions", "launch_ros.descriptions")
class ParameterValue:
    """A parameter value, possibly from substitutions, with an optional type."""

    def __init__(self, value: Any, *, value_type: Any = None) -> None:
        self.value = value
        self.value_type = value_type

    def evaluate(self, context: Any) -> Any:
        """Return the typed value."""
        value = self.value
        if isinstance(value, (Substitution, list, tuple, str)) and not _is_plain_list(value):
            text = perform_substitutions(context, normalize_to_list_of_substitutions(value))
            if self.value_type is str:
                return text
            value = yaml.safe_load(text) if text else ""
        if self.value_type in (int, float, bool, str) and not isinstance(value, self.value_type):
            value = self.value_type(value)
        return list(value) if isinstance(value, tuple) else value


def _is_plain_list(value: Any) -> bool:
    return isinstance(value, (list, tuple)) and all(
        isinstance(v, (bool, int, float)) for v in value
    )


@expose("launch_ros.parameter_descriptions", "launch_ros.descriptions")
class ParameterFile:
    """A params YAML file, optionally with substitutions inside (`allow_substs`)."""

    def __init__(self, param_file: Any, *, allow_substs: Any = False) -> None:
        self.param_file = normalize_to_list_of_substitutions(
            os.fspath(param_file) if isinstance(param_file, os.PathLike) else param_file
        )
        self.allow_substs = allow_substs

    def evaluate(self, context: Any) -> Path:
        """Return the path (a substituted copy when `allow_substs` is set)."""
        path = perform_substitutions(context, self.param_file)
        allow = self.allow_substs
        if not isinstance(allow, bool):
            allow = (
                perform_substitutions(context, normalize_to_list_of_substitutions(allow)).lower()
                == "true"
            )
        if not allow:
            return Path(path)
        text = Path(path).read_text()
        with tempfile.NamedTemporaryFile("w", prefix="launch_params_", delete=False) as handle:
            handle.write(perform_substitutions(context, parse_substitution(text)))
        return Path(handle.name)


@expose("launch_ros.parameter_descriptions", "launch_ros.descriptions")
class Parameter:
    """One parameter given as a rule (`-p name:=value`)."""

    def __init__(self, name: Any, value: Any, *, value_type: Any = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.value = (
            value
            if isinstance(value, ParameterValue)
            else ParameterValue(value, value_type=value_type)
        )

    def evaluate(self, context: Any) -> tuple[str, Any]:
        """Return (name, value)."""
        return perform_substitutions(context, self.name), self.value.evaluate(context)


def _normalize_value(value: Any) -> Any:
    if isinstance(value, (ParameterValue, bool, int, float, bytes)):
        return value
    if isinstance(value, str):
        return ParameterValue(value, value_type=str)
    if isinstance(value, Substitution):
        return ParameterValue(value)
    if isinstance(value, Sequence):
        kinds = {type(v) for v in value}
        if kinds and kinds <= {int, float} and float in kinds:
            return [float(v) for v in value]
        if kinds and kinds <= {bool, int, float, str}:
            return list(value)
        if any(isinstance(v, Substitution) for v in value):
            return ParameterValue(list(value))
        return [ParameterValue(v) for v in value]
    raise TypeError(f"Unexpected type for parameter value {value!r}")


def _normalize_dict(params: Mapping, prefix: str = "") -> dict[Any, Any]:
    normalized: dict[Any, Any] = {}
    for name, value in params.items():
        key: str | tuple[Any, ...] = (
            name if isinstance(name, str) else tuple(normalize_to_list_of_substitutions(name))
        )
        if prefix:
            key = f"{prefix}.{key}" if isinstance(key, str) else (prefix, ".", *key)
        if isinstance(value, Mapping):
            normalized.update(_normalize_dict(value, key if isinstance(key, str) else ""))
        else:
            normalized[key] = _normalize_value(value)
    return normalized


def normalize_parameters(parameters: Any) -> list[Any]:
    """Normalize `Node(parameters=[...])`: dicts, files (str/Path/substitutions), rules."""
    if isinstance(parameters, str) or not isinstance(parameters, Sequence):
        raise TypeError(f"Expecting list of parameters, got {parameters}")
    result: list[Any] = []
    for item in parameters:
        if isinstance(item, Mapping):
            result.append(_normalize_dict(item))
        elif isinstance(item, (Parameter, ParameterFile)):
            result.append(item)
        else:
            result.append(ParameterFile(item))
    return result


def _evaluate_key(context: Any, key: Any) -> str:
    if isinstance(key, str):
        return key
    return "".join(k if isinstance(k, str) else k.perform(context) for k in key)


def evaluate_parameter_dict(context: Any, params: Mapping) -> dict[str, Any]:
    """Perform the substitutions of a normalized parameter dict."""
    result: dict[str, Any] = {}
    for key, value in params.items():
        if isinstance(value, ParameterValue):
            value = value.evaluate(context)
        elif isinstance(value, list):
            value = [v.evaluate(context) if isinstance(v, ParameterValue) else v for v in value]
        result[_evaluate_key(context, key)] = value
    return result


def write_params_file(node_key: str, params: Mapping[str, Any]) -> str:
    """Write `{node_key: {ros__parameters: params}}` to a temporary file, as launch_ros does."""
    with tempfile.NamedTemporaryFile("w", prefix="launch_params_", delete=False) as handle:
        WRITTEN_FILES.append(handle.name)
        yaml.dump({node_key: {"ros__parameters": dict(params)}}, handle, default_flow_style=False)
        return handle.name
