"""`lesson.history(node)`: each change of a node's parameters since it started, and its source.

Built from the lab's parameter journal (core/param_journal.py): /parameter_events tell which
node changed which value, never who asked; the course's doors (`%ros2`, the terminal's `ros2`,
the panel, `lesson.reset`) record their requests first, so an event that matches a request
(same node, parameter and value, within `MATCH_WINDOW_S`) gets that door; one that matches
none came from the node itself or another node. The course's starts (`%ros2 run`,
`lesson.run`, a launch file) record their `--ros-args`, which name the start-up overrides.
Building is pure (records in, table out); only `node_history` reads the file.
"""

from __future__ import annotations

import html
import json
import os
import time
from dataclasses import dataclass
from typing import Any

from ..ros2.paramfile import ROS_ARGS, ParamFileError, read_param_file, ros_arguments
from ..ros2.values import NOT_SET, ParamValue, from_journal, parse_value

__all__ = [
    "HistoryEntry",
    "ParameterHistory",
    "build_history",
    "format_value",
    "named_starts",
    "node_history",
]

MATCH_WINDOW_S = 30.0  # a request's event arrives within this (a loaded machine included)
NAME_WINDOW_S = 60.0  # a started executable's node name is learnt from its log within this
OTHER = "the node itself or another node"
DOORS = {
    "%ros2": "%ros2 magic",
    "terminal": "terminal ros2",
    "panel": "parameter panel",
    "lesson.reset": "lesson.reset",
    "Python": "Python (course API)",
}


@dataclass(frozen=True)
class HistoryEntry:
    """One change of one parameter: when, what, and through which door."""

    number: int
    wall: float
    sim: float | None
    name: str
    old: ParamValue | None
    new: ParamValue | None  # None: deleted
    source: str
    stamp: float | None = None  # the /parameter_events stamp, when an event was seen


def door_label(door: str) -> str:
    """Return how the history names a door (`terminal|params file x.yaml` → the file first)."""
    base, _bar, what = door.partition("|")
    label = DOORS.get(base, base)
    return f"{what} ({label})" if what else label


def format_value(value: ParamValue | None) -> str:
    """Return a value as `ros2 param dump` writes it (`0.2`, `true`, `[1, 2]`); `—` unknown."""
    if value is None:
        return "—"
    raw = value.python
    if isinstance(raw, bool):
        return "true" if raw else "false"
    if isinstance(raw, str):
        return json.dumps(raw)
    if isinstance(raw, list):
        return "[" + ", ".join(format_value(ParamValue.of(v)) for v in raw) + "]"
    return repr(raw) if isinstance(raw, float) else str(raw)


def _ros_arguments(record: dict[str, Any]) -> list[tuple[str, str]]:
    """Return the (flag, value) pairs rcl reads from a start record's arguments (those after
    its first `--ros-args`, as core/param_journal.py records them)."""
    return ros_arguments([ROS_ARGS, *(str(a) for a in record.get("args") or [])])


def _remapped_node(pairs: list[tuple[str, str]]) -> str | None:
    """Return the node name `-r __node:=x` (and `__ns`) give, if any."""
    name = ns = None
    for flag, rule in pairs:
        if flag in ("-r", "--remap") and ":=" in rule:
            key, _sep, value = rule.partition(":=")
            if key.endswith("__node"):
                name = value
            elif key.endswith("__ns"):
                ns = value
    if name is None:
        return None
    return f"{(ns or '').rstrip('/')}/{name}" if not name.startswith("/") else name


def _file_values(path: str, node: str, cwd: str | None) -> list[tuple[str, ParamValue]]:
    try:
        return read_param_file(path, target_node=node, cwd=cwd, at_start=True)
    except (ParamFileError, OSError):
        return []  # no section for this node, or the file is gone: it overrode nothing


def _run_overrides(record: dict[str, Any], node: str) -> list[tuple[str, ParamValue, str]]:
    cwd = record.get("cwd")
    door = door_label(str(record.get("door")))
    found: list[tuple[str, ParamValue, str]] = []
    for flag, value in _ros_arguments(record):
        if flag in ("-p", "--param") and ":=" in value:
            name, _sep, text = value.partition(":=")
            found.append((name, parse_value(text), f"-p at start ({door})"))
        elif flag == "--params-file":
            label = f"params file {os.path.basename(value)}"
            found += [(n, v, label) for n, v in _file_values(value, node, cwd)]
    return found


def _launch_overrides(record: dict[str, Any], node: str) -> list[tuple[str, ParamValue, str]]:
    launch = f"launch file {os.path.basename(str(record.get('launch_file') or '?'))}"
    found: list[tuple[str, ParamValue, str]] = []
    for source in record.get("sources") or []:
        if source.get("kind") == "file" and source.get("path"):
            label = f"params file {os.path.basename(source['path'])} ({launch})"
            found += [(n, v, label) for n, v in _file_values(source["path"], node, None)]
        else:
            for name, value in (source.get("values") or {}).items():
                found.append((name, ParamValue.of(value), launch))
    return found


def _started_node(records: list[dict[str, Any]], index: int) -> str | None:
    """Return the node a start record started: named in it, by a remap, or learnt later."""
    record = records[index]
    if record.get("node"):
        return str(record["node"])
    remapped = _remapped_node(_ros_arguments(record))
    if remapped:
        return remapped
    for later in records[index + 1 :]:
        if later.get("wall", 0) - record.get("wall", 0) > NAME_WINDOW_S:
            break
        if later.get("t") == "named" and later.get("exe") == record.get("exe"):
            return str(later.get("node"))
    # A terminal's `ros2 run` prints its log to the terminal, not to the course: the name the
    # same executable had when a lesson ran it.
    named = [r for r in records if r.get("t") == "named" and r.get("exe") == record.get("exe")]
    return str(named[-1].get("node")) if named else None


@dataclass(frozen=True)
class ParameterHistory:
    """A node's parameter changes since it started; shown as a table in a notebook."""

    node: str
    started: float | None  # wall time of the course's start of the node (None: not seen)
    start_door: str
    overrides: tuple[tuple[str, ParamValue, str], ...]
    entries: tuple[HistoryEntry, ...]

    def startup_value(self, name: str) -> ParamValue | None:
        """Return `name`'s value right after the start, if the history knows it."""
        for entry in self.entries:
            if entry.name == name and entry.source not in self._override_sources():
                return entry.old
        known = [v for n, v, _s in self.overrides if n == name]
        return known[-1] if known else None

    def _override_sources(self) -> set[str]:
        return {s for _n, _v, s in self.overrides}

    def changed_names(self) -> list[str]:
        """Return the parameters changed after the start, in order of first change."""
        own = self._override_sources()
        return list(dict.fromkeys(e.name for e in self.entries if e.source not in own))

    def _rows(self) -> list[tuple[str, str, str, str, str, str]]:
        return [
            (
                f"#{e.number}",
                "—" if e.sim is None else f"{e.sim:.2f} s",
                time.strftime("%H:%M:%S", time.localtime(e.wall)),
                e.name,
                f"{format_value(e.old)} → {'(deleted)' if e.new is None else format_value(e.new)}",
                e.source,
            )
            for e in self.entries
        ]

    def _title(self) -> str:
        if self.started is None:
            return f"Parameter changes of {self.node} (its start was not seen by the course)"
        return f"Parameter changes of {self.node} since it started ({self.start_door})"

    def __repr__(self) -> str:
        """The plain-text table: no clock times, so that a re-run prints the same text."""
        if not self.entries:
            return f"{self._title()}: none.\n"
        rows = [(n, name, change, source) for n, _s, _w, name, change, source in self._rows()]
        widths = [max(len(r[i]) for r in rows) for i in range(3)]
        lines = [f"{self._title()}:"]
        lines += [
            "  ".join(cell.ljust(widths[i]) for i, cell in enumerate(r[:3])) + "  " + r[3]
            for r in rows
        ]
        return "\n".join(lines) + "\n"

    def _repr_html_(self) -> str:
        head = "".join(
            f"<th>{h}</th>"
            for h in ("#", "sim time", "wall time", "parameter", "old → new", "source")
        )
        body = "".join(
            f'<tr id="history{html.escape(self.node.replace("/", "-"))}-{r[0][1:]}">'
            + "".join(
                # the times' class lets a notebook test mask them (tests/nbval_sanitize.cfg)
                f'<td class="history-time">{html.escape(cell)}</td>'
                if column in (1, 2)
                else f"<td>{html.escape(cell)}</td>"
                for column, cell in enumerate(r)
            )
            + "</tr>"
            for r in self._rows()
        )
        empty = "" if self.entries else "<p>No change yet.</p>"
        return f"<b>{html.escape(self._title())}</b><table><tr>{head}</tr>{body}</table>{empty}"


def _latest_start(records: list[dict[str, Any]], node: str) -> int | None:
    found = None
    for index, record in enumerate(records):
        if record.get("t") == "start" and _started_node(records, index) == node:
            found = index
    return found


def _events(records: list[dict[str, Any]], node: str) -> list[dict[str, Any]]:
    """Return the node's event records once each: several listeners (the lab's kernels, its
    `ros2` daemon) record the same event; a record that knows the simulated time is kept."""
    kept: dict[float, dict[str, Any]] = {}
    for record in records:
        if record.get("t") == "event" and record.get("node") == node:
            stamp = float(record.get("stamp") or 0.0)
            if stamp not in kept or (
                kept[stamp].get("sim") is None and record.get("sim") is not None
            ):
                kept[stamp] = record
    return list(kept.values())


class _Builder:
    """Pair events with requests, then walk the changes in time order to know old values."""

    def __init__(self, records: list[dict[str, Any]], node: str) -> None:
        failed = {r.get("id") for r in records if r.get("t") == "failed"}
        self.requests = [
            r
            for r in records
            if r.get("t") == "set" and r.get("node") == node and r.get("id") not in failed
        ]
        self.matched: set[int] = set()
        # (record giving the time, name, new value as stored, the request or None)
        self.changes: list[tuple[dict[str, Any], str, Any, dict[str, Any] | None]] = []

    def _request_for(self, event: dict[str, Any], name: str, stored: Any) -> dict[str, Any] | None:
        for index, request in enumerate(self.requests):
            if index in self.matched or request.get("name") != name:
                continue
            if request.get("value") != stored:
                continue
            if -1.0 <= event["wall"] - request["wall"] <= MATCH_WINDOW_S:
                self.matched.add(index)
                return request
        return None

    def event(self, event: dict[str, Any]) -> None:
        for change in event.get("changes") or []:
            if change.get("kind") == "new":
                continue  # a declaration: part of the node's start, not a change
            name, stored = str(change.get("name")), change.get("value")
            request = self._request_for(event, name, stored)
            self.changes.append((event, name, stored, request))

    def rows(self, overrides: list[Any], started: float | None) -> list[dict[str, Any]]:
        """Return the rows, oldest first: start-up overrides, then every change."""
        changes = list(self.changes)
        changes += [  # requests no kernel saw an event of (no lesson was listening then)
            (r, str(r.get("name")), r.get("value"), r)
            for i, r in enumerate(self.requests)
            if i not in self.matched
        ]
        changes.sort(key=lambda c: c[0]["wall"])
        known: dict[str, ParamValue | None] = {}
        rows = []
        for name, value, source in overrides:
            rows.append(_row({"wall": started}, name, known.get(name), value, source))
            known[name] = value
        for record, name, stored, request in changes:
            old = known.get(name)
            if request is not None and request.get("old") is not None:
                old = from_journal(request["old"])
            new = from_journal(stored)
            new = None if new is None or new.type == NOT_SET else new
            door = str(request.get("door")) if request is not None else ""
            rows.append(_row(record, name, old, new, door_label(door) if door else OTHER))
            known[name] = new
        return rows


def _row(record: dict[str, Any], name: str, old: Any, new: Any, source: str) -> dict[str, Any]:
    return {"wall": record["wall"], "sim": record.get("sim"), "name": name, "old": old,
            "new": new, "source": source, "stamp": record.get("stamp")}  # fmt: skip


def build_history(records: list[dict[str, Any]], node: str) -> ParameterHistory:
    """Return `node`'s history from journal records (oldest first)."""
    start = _latest_start(records, node)
    overrides: list[tuple[str, ParamValue, str]] = []
    started, door = None, ""
    if start is not None:
        record = records[start]
        started = float(record.get("wall", 0.0))
        door = door_label(str(record.get("door")))
        if record.get("door") == "launch":
            overrides = _launch_overrides(record, node)
            door = f"launch file {os.path.basename(str(record.get('launch_file') or '?'))}"
        else:
            overrides = _run_overrides(record, node)
        records = records[start + 1 :]
    builder = _Builder(records, node)
    for event in _events(records, node):
        builder.event(event)
    rows = builder.rows(overrides, started)
    fields = ("wall", "sim", "name", "old", "new", "source", "stamp")
    entries = tuple(HistoryEntry(n, *(r[f] for f in fields)) for n, r in enumerate(rows, 1))
    return ParameterHistory(node, started, door, tuple(overrides), entries)


def node_history(node: str, domain: int | str, *, live: bool = True) -> ParameterHistory:
    """Return the history of `node` in ROS domain `domain` (read from its journal); `live`:
    a node a terminal's `ros2 run` started is named from the graph (see `named_starts`)."""
    from ..core.param_journal import read_journal

    full = node if node.startswith("/") else "/" + node
    records = read_journal(domain)
    return build_history(named_starts(records, full) if live else records, full)


def named_starts(records: list[dict[str, Any]], node: str) -> list[dict[str, Any]]:
    """Return `records` with a `named` record after each start with a pid (a terminal's
    `ros2 run`, whose log goes to the terminal) whose process holds `node` now (its
    /parameter_events publisher): the graph says which node that process started."""
    by_pid = [r for r in records if r.get("t") == "start" and r.get("pid")]
    if not by_pid:
        return records
    from ..lab.drivers import publishers
    from ..ros2.api.nodes_and_params import client

    holders = [p for p in publishers(client(), "/parameter_events") if p.node == node]
    holding = {id(r) for r in by_pid if any(p.runs_in(int(r["pid"])) for p in holders)}
    out: list[dict[str, Any]] = []
    for record in records:
        out.append(record)
        if id(record) in holding:
            out.append({"t": "named", "wall": record.get("wall"), "exe": record.get("exe"),
                        "node": node})  # fmt: skip
    return out
