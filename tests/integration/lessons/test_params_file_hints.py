"""A params file that sets nothing on the node it is given to: the node's own lines, then a hint.

Through `%ros2 run ... --ros-args --params-file`, `lesson.run` and `lesson.launch`, against the
real tutorial node of the course workspace; the terminal's `ros2 run` adds nothing.
"""

from __future__ import annotations

import os
import re
import select
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.config.course import load_course_settings
from course_lib.core import ament
from course_lib.core.errors import PackageNotFoundError
from course_lib.lessons import Lesson
from course_lib.notebook.magics import run_line
from course_lib.session.session import get_session

pytestmark = [pytest.mark.ros, pytest.mark.slow]

REPO = Path(__file__).resolve().parents[3]
FIRST_LINE = re.compile(  # the node's first lines (up to 5), as Jazzy prints them
    r"(\[INFO\] \[\d+\.\d+\] \[param_vel_node\]: Velocity parameter is: 0\.000000\n){1,5}"
)
OTHER_NODE = "/some_other_node:\n  ros__parameters:\n    velocity: 0.9\n"
MISSPELT = "/param_vel_node:\n  ros__parameters:\n    velocty: 0.3\n"
RIGHT = "/param_vel_node:\n  ros__parameters:\n    velocity: 0.0\n"
INTEGER = "/param_vel_node:\n  ros__parameters:\n    velocity: 1\n"


def _has_workspace() -> bool:
    try:
        return "param_vel" in ament.package_executables("parameter_tests", ament.workspace_env())
    except PackageNotFoundError:
        return False


if not _has_workspace():
    pytest.skip("rosject not built", allow_module_level=True)


def _other_node_hint(path: Path) -> str:
    return (
        f"no top-level key of {path} ('/some_other_node') names a node this started "
        "(/param_vel_node), so ROS applied nothing: use '/param_vel_node:' or '/**:'."
    )


def _misspelt_hint(path: Path) -> str:
    return (
        f"/param_vel_node does not declare 'velocty' (set in {path}), so ROS ignored it; "
        "did you mean 'velocity'?"
    )


@pytest.fixture(scope="module")
def lesson() -> Iterator[Lesson]:
    session = get_session()
    course_lesson = Lesson(9, session, load_course_settings())
    yield course_lesson
    course_lesson.stop_nodes()
    session.close()


@pytest.fixture
def files(tmp_path: Path) -> dict[str, Path]:
    found = {}
    for name, text in (
        ("other", OTHER_NODE),
        ("misspelt", MISSPELT),
        ("right", RIGHT),
        ("integer", INTEGER),
    ):
        found[name] = tmp_path / f"{name}.yaml"
        found[name].write_text(text, encoding="utf-8")
    return found


def test_magic_run_with_a_key_for_another_node(lesson: Lesson, files) -> None:  # type: ignore[no-untyped-def]
    result = run_line(f"run parameter_tests param_vel --ros-args --params-file {files['other']}")
    assert FIRST_LINE.fullmatch(result.output.text)  # the node's own line, as Jazzy prints it
    assert result.hints == [_other_node_hint(files["other"])]
    assert result.text == result.output.text + f"Hint: {result.hints[0]}\n"


def test_magic_run_with_an_undeclared_parameter(lesson: Lesson, files) -> None:  # type: ignore[no-untyped-def]
    result = run_line(
        f"run parameter_tests param_vel --ros-args --params-file {files['misspelt']}"
    )
    assert FIRST_LINE.fullmatch(result.output.text)
    assert result.hints == [_misspelt_hint(files["misspelt"])]


def test_magic_run_with_a_right_file_has_no_hint(lesson: Lesson, files) -> None:  # type: ignore[no-untyped-def]
    result = run_line(f"run parameter_tests param_vel --ros-args --params-file {files['right']}")
    assert FIRST_LINE.fullmatch(result.output.text) and result.hints == []


def test_lesson_run_with_a_key_for_another_node(lesson: Lesson, files) -> None:  # type: ignore[no-untyped-def]
    lines = lesson.run(
        "parameter_tests", "param_vel", "--ros-args", "--params-file", str(files["other"])
    )
    assert lines.hints == [_other_node_hint(files["other"])]
    assert repr(lines).endswith(f"Velocity parameter is: 0.000000\nHint: {lines.hints[0]}\n")
    assert 'class="course-hint"' in (lines._repr_html_() or "")


def test_an_integer_for_a_double_in_the_file(lesson: Lesson, files) -> None:  # type: ignore[no-untyped-def]
    path = files["integer"]
    hint = (
        f"in {path}: 'velocity' is a double (a number with a decimal point); `1` was read as "
        "an integer and ROS does not convert it: write `1.0`."
    )
    lines = lesson.run("parameter_tests", "param_vel", "--ros-args", "--params-file", str(path))
    assert lines.lines[1] == (  # rclpy's own last words, as a terminal shows them
        "rclpy.exceptions.InvalidParameterTypeException: Trying to set parameter 'velocity' "
        "to '1' of type 'INTEGER', expecting type 'DOUBLE': velocity"
    )
    assert lines.hints == [hint]
    result = run_line(f"run parameter_tests param_vel --ros-args --params-file {path}")
    assert result.output.text.startswith("Traceback (most recent call last):\n")
    assert result.hints == [hint]


def test_a_params_file_that_is_not_there_or_not_yaml(lesson: Lesson, files, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """rcl cannot open or parse the file: the node logs an error, then rclpy's traceback, and
    ends. Both doors wait for the end and say so (as a terminal does), with the file's hint."""
    missing = tmp_path / "nope.yaml"
    lines = lesson.run("parameter_tests", "param_vel", "--ros-args", "--params-file", str(missing))
    assert lines.lines[1].startswith("rclpy._rclpy_pybind11.RCLError: failed to initialize rcl")
    assert lines.lines[1:] == [lines.lines[1], "[ros2run]: Process exited with failure 1"]
    assert lines.hints == [
        f"there is no file {missing} (a relative path starts in the folder the node runs in): "
        f"check its name and folder, for example with `%ls {tmp_path}`."
    ]
    malformed = tmp_path / "malformed.yaml"
    malformed.write_text("/param_vel_node:\n  ros__parameters:\n    velocity: [0.3\n")
    result = run_line(f"run parameter_tests param_vel --ros-args --params-file {malformed}")
    assert result.output.exit_code == 1 and not lesson.session.children  # it ended, gone
    text = result.output.text
    assert text.startswith("[ERROR] ") and "Failed to parse global arguments\n" in text
    assert "Error parsing a event near line 3" in text.splitlines()[-1]  # rclpy's last line
    assert result.hints[0].startswith(f"{malformed} is not a params file ROS can read (rcl")


def test_lesson_launch_with_an_undeclared_parameter(lesson: Lesson, files) -> None:  # type: ignore[no-untyped-def]
    run = lesson.launch(
        "parameter_tests", "test_parameters_file.launch.py", f"params_file:={files['misspelt']}"
    )
    try:
        assert run.hints == [_misspelt_hint(files["misspelt"])]
        assert repr(run).endswith(f"\nHint: {run.hints[0]}\n")
    finally:
        run.stop()
    right = lesson.launch(
        "parameter_tests", "test_parameters_file.launch.py", f"params_file:={files['right']}"
    )
    try:
        assert right.hints == [] and right._repr_html_() is None
    finally:
        right.stop()


def _first_line(proc: subprocess.Popen, deadline: float) -> str:
    """Return the process's first stderr line (empty if none came before the deadline)."""
    assert proc.stderr is not None
    while time.monotonic() < deadline:
        ready, _, _ = select.select([proc.stderr], [], [], 0.5)
        if ready:
            return proc.stderr.readline()
    return ""


def test_terminal_run_prints_the_node_lines_only(lesson: Lesson, files) -> None:  # type: ignore[no-untyped-def]
    env = {**ament.workspace_env(), **lesson.session.env, "PYTHONPATH": str(REPO)}
    proc = subprocess.Popen(
        [sys.executable, "-m", "course_lib.ros2.command.cli", "run", "parameter_tests",
         "param_vel", "--ros-args", "--params-file", str(files["other"])],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        start_new_session=True,
    )  # fmt: skip
    try:
        first = _first_line(proc, deadline=time.monotonic() + 30.0)  # slow under load
        os.killpg(proc.pid, signal.SIGINT)  # Ctrl-C to the terminal's foreground group
        stdout, stderr = proc.communicate(timeout=20)
        stderr = first + stderr
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert "Velocity parameter is: 0.000000" in stderr
    assert "Hint" not in stdout + stderr
