"""Issue 63: the hints and the history select a params file's sections by rcl's rules, the same
as the lesson 9 exercise (tests/unit/lessons/skills/test_file_values_keys.py): a key the hints
accept is never a "wrong key" to the exercise, nor the reverse."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.notebook import hints
from course_lib.notebook.history import build_history

NODE = "/param_vel_node"
DECLARED = {NODE: ["start_type_description_service", "use_sim_time", "velocity"]}

# (the YAML that names the section, whether rcl gives it to /param_vel_node)
KEYS = [
    ('"/param_vel_node":', True),
    ('"param_vel_node":', True),
    ('"/**":', True),
    ('"**":', True),
    ('"/*":', True),
    ('"*":', True),
    ('"/**/param_vel_node":', True),
    ('"/**":\n  "param_vel_node":', True),  # nested: rcl joins them into /**/param_vel_node
    ('"ns":\n  "param_vel_node":', False),  # /ns/param_vel_node
    ('"/*/param_vel_node":', False),
    ('"/param*":', False),  # rcl refuses `param*`; it is no pattern
    ('"/param_vel":', False),
]


def params_text(key: str) -> str:
    """Return a params file whose section `key` sets velocity (and a misspelt name)."""
    indent = " " * (2 * (key.count("\n") + 1))
    return f"{key}\n{indent}ros__parameters:\n{indent}  velocity: 0.12\n{indent}  velocty: 0.12\n"


@pytest.mark.parametrize(("key", "selects"), KEYS)
def test_hints_read_the_keys_rcl_reads(key: str, selects: bool) -> None:
    found = hints.section_hints("p.yaml", hints.file_sections(params_text(key)), DECLARED)
    if selects:  # the section is read: its misspelt name is the hint
        assert len(found) == 1 and "does not declare 'velocty'" in found[0], found
    else:
        assert len(found) == 1 and "applied nothing" in found[0], found


@pytest.mark.parametrize(("key", "selects"), KEYS)
def test_the_history_reads_the_keys_rcl_reads(tmp_path: Path, key: str, selects: bool) -> None:
    (tmp_path / "p.yaml").write_text(params_text(key), encoding="utf-8")
    start = {"t": "start", "wall": 1.0, "door": "%ros2", "exe": "param_vel", "node": NODE,
             "args": ["--params-file", "p.yaml"], "cwd": str(tmp_path)}  # fmt: skip
    overrides = {name: value.value for name, value, _ in build_history([start], NODE).overrides}
    assert overrides == ({"velocity": 0.12, "velocty": 0.12} if selects else {})


def test_the_history_reads_no_params_file_after_the_end_of_ros_arguments(tmp_path: Path) -> None:
    (tmp_path / "p.yaml").write_text(params_text('"/**":'), encoding="utf-8")
    start = {"t": "start", "wall": 1.0, "door": "%ros2", "exe": "param_vel", "node": NODE,
             "args": ["--", "--params-file", "p.yaml"], "cwd": str(tmp_path)}  # fmt: skip
    assert build_history([start], NODE).overrides == ()
