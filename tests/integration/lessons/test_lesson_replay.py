"""A driving lesson saves its run as an offline replay: real world, real node, real events."""

from __future__ import annotations

import os
import re
import time
from collections.abc import Iterator

import pytest

from course_lib.lessons import Lesson, start
from course_lib.lessons.replay import KEEP, ReplayLink
from course_lib.ros2.api import nodes_and_params as api

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

NODE = "/param_vel_node"
NAME = re.compile(r"lesson07-\d{4}-\d\d-\d\d-\d{6}(-\d+)?\.html")


@pytest.fixture(scope="module")
def driven(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Lesson, object]]:
    """Lesson 7's path: world, node, plot, velocity 0.2 for 2 s, then 0.0 until stopped."""
    lesson = start(7)
    lesson.replay.folder = tmp_path_factory.mktemp("my_files") / "replays"
    lesson.world(show=False)
    lesson.run("parameter_tests", "param_vel")
    plot = lesson.speed_plot()
    assert api.param_set(NODE, "velocity", 0.2).successful
    lesson.drive_for(2.0)
    assert api.param_set(NODE, "velocity", 0.0).successful
    lesson.wait_until_stopped()
    plot.close()
    yield lesson, plot
    lesson.stop_nodes()
    lesson.current_world.stop()


def test_the_run_is_saved_with_its_plot_and_marks(driven: tuple[Lesson, object]) -> None:
    lesson, plot = driven
    started = time.perf_counter()
    link = lesson.save_replay()
    took = time.perf_counter() - started
    assert isinstance(link, ReplayLink), link
    assert NAME.fullmatch(link.path.name), link.path.name
    page = link.path.read_text(encoding="utf-8")
    _samples, marks = plot.snapshot()
    labels = [label for _, label in marks]
    # numbered like lesson.history()'s entries
    assert [label.split(" ", 1)[-1] for label in labels] == ["velocity := 0.2", "velocity := 0"]
    assert all(label.startswith("#") for label in labels), labels
    assert page.count('class="mark"') == 2 and "velocity := 0.2" in page
    run = lesson.replay.log.run(lesson.replay.since)
    assert run[-1].pose[0] - run[0].pose[0] > 0.3, "the replay's robot did not drive"
    assert 'href="' not in page.split("<body>")[1].split("<script>")[0]
    assert took < 5.0, f"saving took {took:.1f} s"
    assert f'href="{link.href}"' in link._repr_html_()


def test_the_self_check_saves_the_same_file_and_shows_its_link(
    driven: tuple[Lesson, object], capsys: pytest.CaptureFixture[str]
) -> None:
    lesson, _ = driven
    first = lesson.save_replay()
    lesson.self_check()
    out = capsys.readouterr().out
    assert f"Replay of this run, saved (opens without a kernel): {first.href}" in out
    assert sorted(lesson.replay.folder.iterdir()) == [first.path]


def test_a_rerun_gets_its_own_file_and_old_ones_are_pruned(
    driven: tuple[Lesson, object],
) -> None:
    lesson, _ = driven
    folder = lesson.replay.folder
    first = lesson.save_replay().path
    for n in range(KEEP + 2):  # older runs of this lesson, and another lesson's
        old = folder / f"lesson07-2020-01-01-00000{n}.html"
        old.write_text("old")
        os.utime(old, (1_600_000_000 + n, 1_600_000_000 + n))
    (folder / "lesson11-2020-01-01-000000.html").write_text("other lesson")
    again = start(7)  # the learner runs the first cell again
    assert again.replay.log is lesson.replay.log  # one run log per session, kept
    again.replay.folder = folder
    again._world = lesson._world
    lesson.current_world.wait_for_odom(lambda _r: bool(again.replay.log.run(again.replay.since)))
    second = again.save_replay()
    assert isinstance(second, ReplayLink), second
    assert second.path != first and first.exists() and NAME.fullmatch(second.path.name)
    mine = sorted(folder.glob("lesson07-*.html"))
    assert len(mine) == KEEP
    assert folder.joinpath("lesson07-2020-01-01-000006.html").exists()  # newest old one kept
    assert not folder.joinpath("lesson07-2020-01-01-000000.html").exists()
    assert folder.joinpath("lesson11-2020-01-01-000000.html").exists()


def test_the_link_is_relative_to_the_notebooks() -> None:
    from course_lib.lessons.files import LEARNER_DIR

    link = ReplayLink(LEARNER_DIR / "replays" / "lesson07-2026-01-01-000000.html")
    assert link.href == "my_files/replays/lesson07-2026-01-01-000000.html"
    assert '<a href="my_files/replays/lesson07-2026-01-01-000000.html"' in link._repr_html_()


def test_the_run_starts_where_the_lesson_put_the_robot(driven: tuple[Lesson, object]) -> None:
    lesson, _ = driven
    start = lesson.current_world.settings.start_pose
    first = lesson.replay.log.run(lesson.replay.since)[0]
    assert abs(first.pose[0] - start.x_m) < 0.05 and abs(first.pose[1] - start.y_m) < 0.05
