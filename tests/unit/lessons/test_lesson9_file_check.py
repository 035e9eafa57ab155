"""Lesson 9's self-check reads the learner's params file as rcl does (ros2/paramfile.py): any
section that selects /param_vel_node counts, the last one winning, as the node would start."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.lessons.catalogue.l09_load_yaml_at_startup import _file_velocity


@pytest.mark.parametrize(
    ("text", "velocity"),
    [
        ("/param_vel_node:\n  ros__parameters:\n    velocity: 0.3\n", 0.3),
        ("param_vel_node:\n  ros__parameters:\n    velocity: 0.3\n", 0.3),
        ("/**:\n  ros__parameters:\n    velocity: 0.3\n", 0.3),
        ("/*:\n  ros__parameters:\n    velocity: 0.3\n", 0.3),
        (
            "/param_vel_node:\n  ros__parameters:\n    velocity: 0.1\n"
            "/**:\n  ros__parameters:\n    velocity: 0.3\n",
            0.3,
        ),
        ("/other_node:\n  ros__parameters:\n    velocity: 0.3\n", None),
        ("/param_vel*:\n  ros__parameters:\n    velocity: 0.3\n", None),
        ("velocity: [unclosed\n", None),
    ],
)
def test_the_file_gives_the_node_what_rcl_would(
    tmp_path: Path, text: str, velocity: object
) -> None:
    path = tmp_path / "param_vel_node.yaml"
    path.write_text(text)
    assert _file_velocity(path) == velocity


def test_a_missing_file_gives_nothing(tmp_path: Path) -> None:
    assert _file_velocity(tmp_path / "absent.yaml") is None
