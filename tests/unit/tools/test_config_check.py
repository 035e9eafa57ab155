"""`make check-config`: config/ alone and together, the rendered lessons, the exercise plan."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from course_lib.config.commented import commented_yaml
from course_lib.config.course import CourseSettings, TravelExercise
from course_lib.config.simulation import SimulationSettings, StartPose
from course_lib.config.trip import MAX_TRAVEL_M, answer_trip, wrong_trip
from course_lib.core.host.procfs import pid_alive
from course_lib.core.paths import CONFIG_DIR, CONFIG_DIR_ENV, NOTEBOOKS_DIR, REPO_ROOT
from course_lib.core.waiting import wait_until
from course_lib.lessons.texts import TEMPLATES, render_cells, settings_used
from course_lib.tools.config_check import HEADERS, check_config, settings_table_rows


def _config(tmp_path: Path, name: str, old: str, new: str) -> Path:
    folder = tmp_path / "config"
    shutil.copytree(CONFIG_DIR, folder)
    text = (folder / name).read_text()
    assert old in text, f"{name} has no {old!r} any more: update this test"
    (folder / name).write_text(text.replace(old, new))
    return folder


def test_the_shipped_config_is_valid_alone_and_together() -> None:
    report = check_config(CONFIG_DIR)
    assert report.ok, report.render()


@pytest.mark.parametrize(
    ("name", "old", "new", "words"),
    [
        (
            "course.yaml",
            "default_velocity_mps: 0.2",
            "default_velocity_mps 0.2",
            "has no colon after its key",
        ),
        (
            "course.yaml",
            "default_velocity_mps: 0.2",
            "default_velocity_mps: 0.3",
            "allowed: >= 0.05",
        ),
        ("simulation.yaml", "  y_m: 0.0", "  y_m: -1.5", "overlaps obstacle_wall"),
        ("simulation.yaml", "  x_m: 0.0", "  x_m: 1.5", "obstacle_box is 0.75 m ahead"),
        ("simulation.yaml", "  x_m: 0.0", "  x_m: 4.5", "the edge of the floor"),
        (
            "course.yaml",
            "  timeout_s: 30.0",
            "  timeout_s: 6.0",
            "the answer's trip alone takes 5 s",
        ),
    ],
)
def test_check_config_names_file_line_key_and_what_to_do(
    tmp_path: Path, name: str, old: str, new: str, words: str
) -> None:
    report = check_config(_config(tmp_path, name, old, new))
    assert not report.ok
    text = report.render()
    assert words in text, text
    assert "Try: " in text and ", line " in text, text


def test_every_problem_is_listed_not_only_the_first(tmp_path: Path) -> None:
    folder = _config(tmp_path, "simulation.yaml", "  odom_hz: 50.0", "  odom_hz: 5000")
    text = (folder / "simulation.yaml").read_text().replace("  samples: 360", "  sample: 360")
    (folder / "simulation.yaml").write_text(text)
    (folder / "hub.yaml").write_text("")
    report = check_config(folder)
    keys = [p.key for p in report.problems]
    assert keys == ["rates.odom_hz", "lidar.sample", "(file)"], report.render()


def test_a_missing_file_says_how_to_restore_it(tmp_path: Path) -> None:
    folder = _config(tmp_path, "course.yaml", "show_hints", "show_hints")
    (folder / "course.yaml").unlink()
    text = check_config(folder).render()
    assert "course.yaml: (file): is missing" in text and "git checkout" in text, text


def test_make_check_config_passes_on_the_shipped_config() -> None:
    # Its speed (under a second) is a bench figure: bench/config_check.py.
    done = subprocess.run(
        [sys.executable, "-m", "course_lib", "check-config"], cwd=REPO_ROOT, check=False
    )
    assert done.returncode == 0


@pytest.mark.parametrize("target", [0.2, 0.55, 0.77, 1.0, 1.2, 1.37, 1.5])
@pytest.mark.parametrize("velocity", [0.05, 0.15, 0.2, 0.26])
def test_every_allowed_target_has_an_answer_and_a_clearly_wrong_attempt(
    target: float, velocity: float
) -> None:
    tolerance = 0.02
    answer = answer_trip(target, tolerance, velocity)
    assert answer is not None
    assert abs(answer.distance_m - target) <= tolerance / 2 + 1e-9
    assert answer.distance_m <= MAX_TRAVEL_M + 1e-9
    assert abs(wrong_trip(answer).distance_m - target) > target / 4


def test_the_shipped_notebooks_are_rendered_from_the_shipped_config() -> None:
    import nbformat

    settings = check_config(CONFIG_DIR).settings["course.yaml"]
    for name in TEMPLATES:
        nb = nbformat.read(NOTEBOOKS_DIR / name, as_version=4)
        assert render_cells(name, nb, settings) == [], f"{name}: run `make notebooks`"
        stored = json.loads((NOTEBOOKS_DIR / name).read_text())["metadata"]
        assert stored.get("course_settings") == settings_used(name, settings), name


def test_templates_show_other_settings() -> None:
    import nbformat

    other = CourseSettings(0.15, False, TravelExercise(1.2, 0.1, 30.0))
    nb = nbformat.read(NOTEBOOKS_DIR / "11_beyond_the_tutorial.ipynb", as_version=4)
    # the travel exercise's three cells, and the saved-panel exercise's prose (its velocity)
    assert len(render_cells("11_beyond_the_tutorial.ipynb", nb, other)) == 4
    sources = "\n".join(c.source for c in nb.cells)
    assert "**1.20 m** (within 10 cm)" in sources
    assert "travel_time 8.0\nparam set /descriptor_vel_node velocity 0.15" in sources


def test_start_pose_turned_to_free_floor_is_accepted() -> None:
    from course_lib.config.together import free_distance_m

    assert free_distance_m(SimulationSettings(start_pose=StartPose(1.0, 0.5, 90.0))) > 1.3


def test_the_shipped_comments_are_what_the_schema_writes() -> None:
    report = check_config(CONFIG_DIR)
    for name, header in HEADERS.items():
        written = commented_yaml(report.settings[name], header)
        shipped = (CONFIG_DIR / name).read_text()
        assert shipped == written, f"{name}: run `make check-config ARGS=--write-comments`"


def test_the_guide_table_lists_every_setting_with_its_range() -> None:
    guide = (REPO_ROOT / "book" / "guides" / "instructor-settings.md").read_text()
    missing = [row for row in settings_table_rows() if row not in guide]
    assert not missing, (
        "book/guides/instructor-settings.md lacks these rows (course_lib.tools.config_check):\n"
        + "\n".join(missing)
    )


@pytest.mark.parametrize("command", ["lab", "notebooks", "doctor"])
def test_a_broken_config_stops_the_command_before_anything_starts(
    tmp_path: Path, command: str
) -> None:
    folder = _config(
        tmp_path, "course.yaml", "default_velocity_mps: 0.2", "default_velocity_mps 0.2"
    )
    done = subprocess.run(
        [sys.executable, "-m", "course_lib", command],
        cwd=REPO_ROOT,
        env={**os.environ, CONFIG_DIR_ENV: str(folder)},
        capture_output=True,
        text=True,
        timeout=30,
        check=False,
    )
    assert done.returncode == 1, done.stdout + done.stderr
    assert "has no colon after its key" in done.stdout + done.stderr
    assert "Traceback" not in done.stderr and "ROS_DOMAIN_ID=" not in done.stdout


def test_a_config_folder_without_hub_yaml_is_complete(tmp_path: Path) -> None:
    """The learners' copy of a class carries no hub.yaml (only the hub reads it, as root: it
    may hold the demo's password); `make doctor` in their lab checks the rest."""
    folder = _config(tmp_path, "course.yaml", "show_hints", "show_hints")
    (folder / "hub.yaml").unlink()
    report = check_config(folder)
    assert report.ok, report.render()
    assert "config/: course.yaml, simulation.yaml are valid" in report.render(), report.render()


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM])
def test_a_lab_stopped_during_its_config_check_leaves_no_checker_behind(
    tmp_path: Path, stop: signal.Signals
) -> None:
    """The lab checks config/ in a child it forks; the lab stopped alone (not its process
    group) ends that child too, and starts nothing."""
    folder = tmp_path / "config"
    shutil.copytree(CONFIG_DIR, folder)
    (folder / "course.yaml").unlink()
    os.mkfifo(folder / "course.yaml")  # the check blocks reading it: stopped mid-check
    lab = subprocess.Popen(
        [sys.executable, "-m", "course_lib", "lab"],
        cwd=REPO_ROOT,
        env={**os.environ, CONFIG_DIR_ENV: str(folder)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        checker = wait_until(lambda: _children(lab.pid), 30.0, message="no checker forked")[0]
        wait_until(lambda: _blocked_on_fifo(checker), 10.0, message="the check never read it")
        lab.send_signal(stop)
        out, err = lab.communicate(timeout=10)
        assert lab.returncode == 130, out + err
        assert "Traceback" not in err and "ROS_DOMAIN_ID=" not in out
        assert not pid_alive(checker), "the config check outlived its lab"
    finally:
        lab.kill()
        with contextlib.suppress(OSError):  # a checker left behind: let its open return
            fd = os.open(folder / "course.yaml", os.O_WRONLY | os.O_NONBLOCK)
            os.close(fd)


def _children(pid: int) -> list[int]:
    path = Path(f"/proc/{pid}/task/{pid}/children")
    return [int(c) for c in path.read_text().split()] if path.exists() else []


def _blocked_on_fifo(pid: int) -> bool:
    wchan = Path(f"/proc/{pid}/wchan").read_text()  # opening it, no writer yet
    return wchan in {"fifo_open", "wait_for_partner"}
