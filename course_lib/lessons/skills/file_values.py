"""What a file gives a node at start-up: the params file a command line passes, and the value
a params file or a launch file gives one parameter, or why it gives none (read, not run).

A params file is read as rcl reads it (ros2/paramfile.py holds rcl's rules): a section's name
must select the node, the value must sit under `ros__parameters:`, and a misspelt name is kept
silently as an undeclared override.
"""

from __future__ import annotations

import difflib
import logging
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from ...ros2.paramfile import (
    PARAMS_KEY,
    Section,
    key_matches,
    load_params_text,
    node_sections,
    params_files,
)

__all__ = [
    "UNREAD_SECTIONS",
    "FileValue",
    "launch_file_value",
    "params_file_of",
    "params_file_value",
]

_log = logging.getLogger(__name__)


def params_file_of(argv: list[str], cwd: Path) -> Path | None:
    """Return the (first) params file a node's command line passes (`--ros-args
    --params-file FILE`, as rcl reads its arguments), if any."""
    for value in params_files(argv)[:1]:
        path = Path(value)
        return path if path.is_absolute() else cwd / path
    return None


@dataclass(frozen=True)
class FileValue:
    """What a file gives the node: its value, or why it gives none.

    `problem`: "" (a value), integer, missing_file, unreadable, wrong_key (`key`: the top key),
    no_parameter (a launch file sets none); for a params file also undeclared (`key`: the
    misspelt name rcl keeps as an override nobody declares), nested (`key`: the dotted name of
    the value one level too deep), file_sets_none (`key`: the node's section), and what rcl
    refuses to read: no_ros_parameters (`written`: the first name under `key`, without
    `ros__parameters:` between), empty_section (`key:` with nothing under it), no_node_key.
    `written`: the value as the file writes it (or the name, for no_ros_parameters).
    """

    value: float | None = None
    problem: str = ""
    written: str = ""
    key: str = ""


# what rcl refuses to read in a params file (the node ends at start-up)
UNREAD_SECTIONS = ("no_ros_parameters", "empty_section", "no_node_key")
_EVERY_NODE = ("use_sim_time", "start_type_description_service")  # rclpy declares them


def _typed(value: Any) -> FileValue:
    if value is None:
        return FileValue(problem="no_parameter")
    if isinstance(value, int) and not isinstance(value, bool):
        return FileValue(problem="integer", written=str(value))
    if isinstance(value, float):
        return FileValue(value=value)
    return FileValue(problem="integer", written=repr(value))  # a string, a list: no double


def _flat(tree: dict[Any, Any], prefix: str = "") -> dict[str, Any]:
    """Return the values of a `ros__parameters` mapping by dotted name, as rcl names them."""
    found: dict[str, Any] = {}
    for name, value in tree.items():
        full = f"{prefix}{name}"
        found.update(_flat(value, full + ".") if isinstance(value, dict) else {full: value})
    return found


def _missing(params: dict[Any, Any], key: str, param: str) -> FileValue:
    """Say why a node's `ros__parameters` lacks `param`: one level too deep, misspelt, or
    not there at all."""
    values = {n: v for n, v in _flat(params).items() if n not in _EVERY_NODE}
    nested = [n for n in values if n.endswith("." + param)]
    if nested:
        return FileValue(problem="nested", key=nested[0], written=str(values[nested[0]]))
    close = difflib.get_close_matches(param, list(values), n=1, cutoff=0.6)
    if close:
        return FileValue(problem="undeclared", key=close[0], written=str(values[close[0]]))
    return FileValue(problem="file_sets_none", key=key)


def _section_value(section: Section, param: str) -> FileValue:
    """Return what one node's section gives `param`, as rcl reads it: values only under
    `ros__parameters:`; a key with nothing under it, or with no value, stops the node."""
    body, key = section.body, section.name
    if not section.has_params:
        if body is None:
            return FileValue(problem="empty_section", key=key)
        if not isinstance(body, dict):
            return FileValue(problem="unreadable")
        if body:
            return FileValue(problem="no_ros_parameters", key=key, written=str(next(iter(body))))
        return FileValue(problem="file_sets_none", key=key)
    params = section.params
    if params is None:
        return FileValue(problem="empty_section", key="ros__parameters")
    if not isinstance(params, dict) or (param in params and params[param] is None):
        return FileValue(problem="unreadable")
    if param in params:
        return _typed(params[param])
    return _missing(params, key, param)


def params_file_value(path: Path, node: str, param: str = "velocity") -> FileValue:
    """Return the `param` a params file gives `node` (as rcl reads it: a section's name must
    select the node, see ros2/paramfile.py)."""
    try:
        data = load_params_text(path.read_text(encoding="utf-8"), name=str(path))
    except FileNotFoundError:
        return FileValue(problem="missing_file")
    except (OSError, yaml.YAMLError, ValueError):  # ValueError: an alias bomb, refused
        return FileValue(problem="unreadable")
    if not isinstance(data, dict) or not data:
        return FileValue(problem="wrong_key", key="(none)")
    if PARAMS_KEY in data:
        return FileValue(problem="no_node_key")
    sections = node_sections(data)
    found = [_section_value(s, param) for s in sections if key_matches(s.name, node)]
    if not found:
        return FileValue(problem="wrong_key", key=sections[0].name)
    unread = [f for f in found if f.problem in (*UNREAD_SECTIONS, "unreadable")]
    given = [f for f in found if f.value is not None or f.problem == "integer"]
    return (unread or given[-1:] or found)[0]  # a later section overrides an earlier one


def launch_file_value(path: Path, executable: str) -> FileValue:
    """Return the velocity a launch file gives `executable`'s node (read, not run)."""
    from ...launch.command.dry_run import dry_run

    try:
        report = dry_run(str(path))
    except Exception as error:  # the learner's own code: anything; the launch shows it too
        _log.info("launch file %s could not be planned: %r", path, error)
        return FileValue(problem="no_parameter")
    for plan in report.nodes:
        if Path(plan.cmd[0]).name == executable:
            found = plan.values.get("velocity")
            return _typed(found[0] if found else None)
    return FileValue(problem="no_parameter")
