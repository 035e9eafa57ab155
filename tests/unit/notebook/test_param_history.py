"""The history builder: journal records in, a node's changes with their sources out (no ROS)."""

from __future__ import annotations

from pathlib import Path

from course_lib.notebook.history import OTHER, build_history, format_value
from course_lib.ros2.values import DOUBLE, ParamValue

NODE = "/param_vel_node"


def _set(wall: float, value: float, door: str, old: float, ident: str) -> dict:
    return {"t": "set", "wall": wall, "id": ident, "door": door, "node": NODE,
            "name": "velocity", "value": [DOUBLE, value], "old": [DOUBLE, old]}  # fmt: skip


def _event(wall: float, value: float, stamp: float, node: str = NODE) -> dict:
    change = {"kind": "changed", "name": "velocity", "value": [DOUBLE, value]}
    return {"t": "event", "wall": wall, "node": node, "stamp": stamp, "sim": 1.5,
            "changes": [change]}  # fmt: skip


def _start(wall: float, *args: str, cwd: str = "/") -> list[dict]:
    return [
        {"t": "start", "wall": wall, "door": "%ros2", "exe": "param_vel", "args": list(args),
         "cwd": cwd},
        {"t": "named", "wall": wall + 2, "exe": "param_vel", "node": NODE},
    ]  # fmt: skip


def _summary(records: list[dict]) -> list[tuple]:
    return [
        (e.old and e.old.value, e.new and e.new.value, e.source)
        for e in build_history(records, NODE).entries
    ]


def test_an_event_takes_the_door_of_the_request_it_matches() -> None:
    records = [
        *_start(100.0),
        _set(110.0, 0.1, "%ros2", 0.0, "a"),
        _event(110.1, 0.1, 1.0),
        _event(110.2, 0.1, 1.0),  # a second kernel journals the same event
        _set(120.0, 1.0, "terminal", 0.1, "b"),
        {"t": "failed", "wall": 120.1, "id": "b"},
        _event(130.0, 0.3, 2.0),  # nobody of the course asked
        _event(131.0, 0.4, 3.0, node="/other"),
        _set(140.0, 0.2, "panel", 0.3, "c"),  # no kernel listened: the request alone
    ]
    assert _summary(records) == [
        (0.0, 0.1, "%ros2 magic"),
        (0.1, 0.3, OTHER),
        (0.3, 0.2, "parameter panel"),
    ]


def test_an_event_heard_twice_keeps_the_simulated_time_of_a_kernel() -> None:
    daemon = {**_event(110.1, 0.1, 1.0), "sim": None}  # the lab's daemon: no world to read
    records = [*_start(100.0), daemon, _event(110.2, 0.1, 1.0)]
    (entry,) = build_history(records, NODE).entries
    assert entry.sim == 1.5


def test_a_request_too_old_for_its_value_is_no_match() -> None:
    records = [*_start(100.0), _set(110.0, 0.1, "%ros2", 0.0, "a"), _event(200.0, 0.1, 1.0)]
    assert [s for _o, _n, s in _summary(records)] == ["%ros2 magic", OTHER]


def test_a_restarted_node_starts_a_new_history_with_its_overrides(tmp_path: Path) -> None:
    (tmp_path / "v.yaml").write_text(
        "param_vel_node:\n  ros__parameters:\n    velocity: 0.05\n"
        "other_node:\n  ros__parameters:\n    velocity: 9.0\n"
    )
    records = [
        *_start(100.0),
        _set(110.0, 0.1, "%ros2", 0.0, "a"),
        *_start(200.0, "--params-file", "v.yaml", "-p", "velocity:=0.07", cwd=str(tmp_path)),
        _set(210.0, 0.2, "terminal", 0.07, "b"),
        _event(210.1, 0.2, 5.0),
    ]
    history = build_history(records, NODE)
    assert _summary(records) == [
        (None, 0.05, "params file v.yaml"),
        (0.05, 0.07, "-p at start (%ros2 magic)"),
        (0.07, 0.2, "terminal ros2"),
    ]
    assert history.started == 200.0
    assert history.startup_value("velocity") == ParamValue(DOUBLE, 0.07)
    assert history.changed_names() == ["velocity"]


def test_the_plain_table_has_no_clock_and_the_html_has_both_times() -> None:
    records = [*_start(100.0), _set(110.0, 0.1, "%ros2", 0.0, "a"), _event(110.1, 0.1, 1.0)]
    history = build_history(records, NODE)
    assert repr(history) == (
        "Parameter changes of /param_vel_node since it started (%ros2 magic):\n"
        "#1  velocity  0.0 → 0.1  %ros2 magic\n"
    )
    assert '<td class="history-time">1.50 s</td>' in history._repr_html_()
    assert repr(build_history([], NODE)) == (
        "Parameter changes of /param_vel_node (its start was not seen by the course): none.\n"
    )


def test_values_read_as_in_a_dump() -> None:
    assert [format_value(ParamValue.of(v)) for v in (True, 1, 0.5, "a", [1.0, 2.0])] == [
        "true", "1", "0.5", '"a"', "[1.0, 2.0]"
    ]  # fmt: skip
