"""A broken config/ in a lesson's first cell, in a fresh kernel: two lines, no traceback."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from jupyter_kernels import Kernel
from suite_env import independent_env

from course_lib.core.paths import CONFIG_DIR, CONFIG_DIR_ENV

pytestmark = [pytest.mark.ros]

FIRST_CELL = "from course_lib.lessons import start\n\nlesson = start(7)"


def _line(name: str, needle: str) -> int:
    text = (CONFIG_DIR / name).read_text().splitlines()
    return next(n for n, line in enumerate(text, 1) if line.startswith(needle))


VELOCITY = _line("course.yaml", "default_velocity_mps:")
START = _line("simulation.yaml", "start_pose:")

CASES = {
    # name: (file, edit of the shipped text, what the first line must say)
    "missing_colon": (
        "course.yaml",
        lambda t: t.replace("default_velocity_mps: 0.2", "default_velocity_mps 0.2"),
        f"course.yaml, line {VELOCITY}: (syntax): not valid YAML: `default_velocity_mps 0.2` "
        "has no colon",
    ),
    "empty": ("course.yaml", lambda t: "", "course.yaml: (file): holds no settings"),
    "out_of_range": (
        "course.yaml",
        lambda t: t.replace("default_velocity_mps: 0.2", "default_velocity_mps: 0.5"),
        f"course.yaml, line {VELOCITY}: default_velocity_mps: 0.5 is out of range "
        "(allowed: >= 0.05",
    ),
    "start_in_a_wall": (
        "simulation.yaml",
        lambda t: t.replace("  y_m: 0.0", "  y_m: -1.5"),
        f"simulation.yaml, line {START}: start_pose: the robot at (0, -1.5) facing 0° overlaps "
        "obstacle_wall",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_broken_config_is_two_lines_in_a_fresh_kernel(case: str, tmp_path: Path) -> None:
    name, edit, first_line = CASES[case]
    folder = tmp_path / "config"
    shutil.copytree(CONFIG_DIR, folder)
    (folder / name).write_text(edit((folder / name).read_text()))
    kernel = Kernel(independent_env(**{CONFIG_DIR_ENV: str(folder)}))
    try:
        out = kernel.run(FIRST_CELL)
    finally:
        kernel.shutdown()
    shown = out.everything.strip()
    assert "Traceback" not in shown and "File " not in shown, shown
    lines = shown.splitlines()
    assert len(lines) == 2, shown
    assert first_line in lines[0], shown
    assert lines[1].startswith("Try: "), shown
