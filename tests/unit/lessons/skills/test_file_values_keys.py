"""Issue 63: the lesson 9 exercise reads a params file's keys by rcl's rules, as the hints and
the history do (tests/unit/notebook/test_params_file_keys.py): a key the hints accept is never
a "wrong key" here, nor the reverse; the file comes from `--ros-args --params-file`."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.lessons.skills.file_values import params_file_of, params_file_value

NODE = "/param_vel_node"

KEYS = [  # as in tests/unit/notebook/test_params_file_keys.py
    ('"/param_vel_node":', True),
    ('"param_vel_node":', True),
    ('"/**":', True),
    ('"**":', True),
    ('"/*":', True),
    ('"*":', True),
    ('"/**/param_vel_node":', True),
    ('"/**":\n  "param_vel_node":', True),
    ('"ns":\n  "param_vel_node":', False),
    ('"/*/param_vel_node":', False),
    ('"/param*":', False),
    ('"/param_vel":', False),
]


@pytest.mark.parametrize(("key", "selects"), KEYS)
def test_the_exercise_reads_the_keys_rcl_reads(tmp_path: Path, key: str, selects: bool) -> None:
    indent = " " * (2 * (key.count("\n") + 1))
    path = tmp_path / "p.yaml"
    path.write_text(f"{key}\n{indent}ros__parameters:\n{indent}  velocity: 0.12\n")
    found = params_file_value(path, NODE)
    assert (found.value, found.problem) == ((0.12, "") if selects else (None, "wrong_key"))


def test_the_exercise_takes_the_params_file_of_the_ros_arguments(tmp_path: Path) -> None:
    argv = ["/x/param_vel", "--params-file", "a.yaml", "--ros-args", "--params-file", "b.yaml"]
    assert params_file_of(argv, tmp_path) == tmp_path / "b.yaml"
    argv = ["/x/param_vel", "--ros-args", "-p", "v:=1", "--", "--params-file", "c.yaml"]
    assert params_file_of(argv, tmp_path) is None


def test_the_exercise_refuses_an_alias_bomb_as_unreadable(tmp_path: Path) -> None:
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    lines += [f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * 10)}]" for i in range(1, 8)]
    path = tmp_path / "bomb.yaml"
    path.write_text("\n".join(lines) + "\n")
    assert params_file_value(path, NODE).problem == "unreadable"
