"""A new or restarted kernel (issue 62: a kernel killed, idle or in a cell) forgets the lesson:
the next cell that uses it says which cell to run, in the learner's terms, never a traceback.

The kernel is the course's own (the `python3` kernelspec, `kernel_launcher`), started for
lesson 7's notebook as JupyterLab starts it (JPY_SESSION_NAME names the notebook).
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from jupyter_kernels import Kernel
from suite_env import independent_env

from course_lib.core.paths import NOTEBOOKS_DIR

pytestmark = pytest.mark.slow

LESSON7 = NOTEBOOKS_DIR / "07_move_the_robot.ipynb"


@pytest.fixture(scope="module")
def kernel() -> Iterator[Kernel]:
    started = Kernel(env={**independent_env(), "JPY_SESSION_NAME": str(LESSON7)})
    yield started
    started.shutdown()


def test_a_lesson_name_says_which_cell_defines_it(kernel: Kernel) -> None:
    out = kernel.run("plot.still()")
    said = out.everything
    assert "`plot` is defined by the cell `plot = lesson.speed_plot()`" in said, said
    assert "run the cells from the top" in said and "`lesson = start(7)`" in said, said
    assert "Traceback" not in said and not out.error, said


def test_ros2_says_the_first_cell_loads_it(kernel: Kernel) -> None:
    out = kernel.run("%ros2 param list /param_vel_node")
    said = out.everything
    assert "`%ros2` is not loaded in this kernel" in said, said
    assert "run the lesson's first cell, `lesson = start(7)`" in said, said
    assert "Traceback" not in said and not out.error, said


def test_a_name_no_cell_defines_keeps_its_traceback(kernel: Kernel) -> None:
    out = kernel.run("velocity_typo + 1")
    assert "NameError" in out.error and "velocity_typo" in out.error, out.everything


def test_the_lessons_first_cell_still_shows_course_errors_as_two_lines(kernel: Kernel) -> None:
    out = kernel.run("from course_lib.lessons import start\nstart(12)")
    assert "there are lessons 1 to 11" in out.everything, out.everything
