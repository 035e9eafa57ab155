"""Issue 62, nothing lost, in a real kernel: the learner's disk fills up (a 2 MiB tmpfs as
their folder) while lesson 8 dumps a params file and the panel saves one. Each write that
cannot be made says so (which file, why, what to do), never as a traceback, and leaves the old
file whole; once there is room again, the same cells save."""

from __future__ import annotations

from pathlib import Path

import pytest
from jupyter_kernels import CellResult, Kernel
from small_disk import fill_disk, small_tmpfs
from suite_env import independent_env

from course_lib.core.files.atomic_files import TEMP_SUFFIX
from course_lib.core.paths import LEARNER_ROOT_ENV

pytestmark = [pytest.mark.ros, pytest.mark.slow]

DUMP = 'lesson.ros2_to_file("param dump /param_vel_node", "my_files/dump/param_vel_node.yaml")'
EDIT = 'lesson.edit_file("my_files/dump/param_vel_node.yaml", "velocity: 0.0", "velocity: 0.2")'
PANEL_LOG = 'print("".join(o["text"] for o in panel.log.outputs), end="")'
FULL = (
    "was not saved: the disk is full. The file as it was before is kept.\nTry: free some "
    "space (old replays in my_files/replays/, for example), then run the cell again.\n"
)


def _said(cell: CellResult) -> str:
    """Return what a cell showed, checked to hold no traceback (the node's log lines, which
    land in whichever cell runs, are left out)."""
    assert not cell.error and "Traceback" not in cell.everything, cell.everything
    return "".join(line for line in cell.text.splitlines(True) if not line.startswith("["))


def test_a_full_disk_is_said_in_a_line_and_loses_nothing(tmp_path: Path) -> None:
    root = tmp_path / "learner"
    with small_tmpfs(root, "2m"):
        notebooks = root / "notebooks"
        dump = notebooks / "my_files" / "dump" / "param_vel_node.yaml"
        dump.parent.mkdir(parents=True)
        kernel = Kernel(independent_env(**{LEARNER_ROOT_ENV: str(root)}))
        try:
            kernel.ok(f"import os\nos.chdir({str(notebooks)!r})")  # where Jupyter starts it
            kernel.ok("from course_lib.lessons import start\nlesson = start(8)")
            kernel.ok("%ros2 run parameter_tests param_vel")
            kernel.ok(DUMP)
            kernel.ok("%ros2 param set /param_vel_node velocity 0.1")
            kernel.ok('panel = lesson.parameter_panel("/param_vel_node")')
            before = dump.read_bytes()
            filler = fill_disk(root)

            said = _said(kernel.run(DUMP))
            assert said == f"FileSaveError: my_files/dump/param_vel_node.yaml {FULL}", said
            assert _said(kernel.run(EDIT)).startswith("FileSaveError: my_files/dump/")
            assert dump.read_bytes() == before  # byte for byte
            assert sorted(p.name for p in dump.parent.iterdir()) == [dump.name]
            kernel.ok("panel.save_button.click()")  # what a click on Save does
            assert _said(kernel.run(PANEL_LOG)) == (
                "Not saved (my_files/panel_params.yaml): the disk is full. No file was written."
                "\nTry: free some space (old replays in my_files/replays/, for example), then "
                "run the cell again.\n"
            )
            assert not any(p.name.endswith(TEMP_SUFFIX) for p in notebooks.rglob(".*"))

            filler.unlink()
            assert _said(kernel.run(DUMP)).startswith(
                "$ ros2 param dump /param_vel_node > my_files/dump/param_vel_node.yaml\n"
            )
            assert "velocity: 0.1" in dump.read_text()
            kernel.ok("panel.log.outputs = ()\npanel.save_button.click()")
            assert _said(kernel.run(PANEL_LOG)).startswith("Saved panel_params.yaml:\n")
            assert "velocity: 0.1" in (dump.parent.parent / "panel_params.yaml").read_text()
        finally:
            kernel.shutdown()
