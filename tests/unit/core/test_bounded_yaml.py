"""A params file whose aliases expand to millions of values is refused at once, with its line.

An attack as much as a mistake: a 1 KB file of nested aliases (`{a: *x, b: *x}` 26 levels
deep) made `ros2 param load` run for minutes. Ordinary aliases still load as PyYAML loads them.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest
import yaml

from course_lib.core.errors import CourseError
from course_lib.core.files.bounded_yaml import MAX_VALUES, YamlTooLarge, safe_load_bounded
from course_lib.launch.command.dry_run import _file_entries
from course_lib.ros2.paramfile import ParamFileError, read_param_file


def _bomb(levels: int = 26) -> str:
    lines = ["/param_vel_node:", "  ros__parameters:", "    l0: &l0 [0.1, 0.2]"]
    lines += [f"    l{n}: &l{n} {{a: *l{n - 1}, b: *l{n - 1}}}" for n in range(1, levels)]
    return "\n".join(lines) + "\n"


def test_an_alias_bomb_is_refused_in_under_a_second_naming_its_line(tmp_path: Path) -> None:
    path = tmp_path / "bomb.yaml"
    path.write_text(_bomb())
    started = time.monotonic()
    with pytest.raises(ParamFileError) as refused:
        read_param_file(str(path))
    assert time.monotonic() - started < 1.0
    output = refused.value.output
    assert output.exit_code == 1 and output.stdout == ""
    assert output.stderr.startswith(f"{path}, line "), output.stderr
    line = int(output.stderr.split("line ")[1].split(":")[0])
    assert _bomb().splitlines()[line - 1].lstrip().startswith("l"), line
    assert f"more than {MAX_VALUES:,} values" in output.stderr


def test_ordinary_aliases_load_as_pyyaml_loads_them() -> None:
    text = "base: &v {x: 1, y: [2, 3]}\nfirst: *v\nsecond: *v\n"
    assert safe_load_bounded(text) == yaml.safe_load(text)
    assert safe_load_bounded("") is None


def test_a_size_just_under_the_limit_loads_and_just_over_is_refused() -> None:
    """Root, two keys and the list twice: 3 + 2 * (n + 1) nodes."""
    limit, n = 1000, 497
    text = f"a: &a [{', '.join(['0'] * n)}]\nb: *a\n"
    assert len(safe_load_bounded(text, limit=limit)["b"]) == n  # 999 nodes
    with pytest.raises(YamlTooLarge) as refused:
        safe_load_bounded(text + "c: *a\n", limit=limit)
    assert refused.value.line == 3


def test_a_launch_dry_run_says_what_rcl_says_of_an_alias(tmp_path: Path) -> None:
    """rcl behind --params-file: "Will not support aliasing at line 4" (the node never starts)."""
    path = tmp_path / "alias.yaml"
    path.write_text("/param_vel_node:\n  ros__parameters:\n    base: &v 0.1\n    velocity: *v\n")
    with pytest.raises(CourseError) as refused:
        _file_entries(str(path), "/param_vel_node", [])
    assert refused.value.message == f"{path}: Will not support aliasing at line 4"
