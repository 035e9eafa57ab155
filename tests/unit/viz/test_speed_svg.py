"""The replay's speed plot: inline SVG, numbered marks with a legend, the latest run only."""

from __future__ import annotations

import re

from course_lib.viz.speed_svg import MAX_POINTS, latest_run, speed_svg

SAMPLES = [(10.0 + i * 0.1, 0.2 if i >= 20 else 0.0) for i in range(60)]
MARKS = [(12.0, "velocity := 0.2"), (15.0, "velocity := 0")]


def test_marks_are_numbered_lines_with_a_legend() -> None:
    svg = speed_svg(SAMPLES, MARKS)
    assert svg.count('class="mark"') == 2
    assert "1 · 12.0 s · velocity := 0.2" in svg and "2 · 15.0 s · velocity := 0" in svg
    assert svg.count('stroke-dasharray="5,3"') == 2


def test_the_line_follows_every_sample() -> None:
    svg = speed_svg(SAMPLES, [])
    points = re.search(r'points="([^"]+)"', svg)
    assert points is not None and len(points.group(1).split()) == len(SAMPLES)
    assert 'class="mark"' not in svg


def test_same_input_same_bytes_and_no_resource() -> None:
    assert speed_svg(SAMPLES, MARKS) == speed_svg(list(SAMPLES), list(MARKS))
    assert "http" not in speed_svg(SAMPLES, MARKS)


def test_a_world_restart_keeps_the_latest_run_and_its_marks() -> None:
    restarted = [*SAMPLES, *((i * 0.1, 0.1) for i in range(30))]
    assert latest_run(restarted) == restarted[60:]
    svg = speed_svg(restarted, [(12.0, "old run"), (1.0, "velocity := 0.1")])
    assert "old run" not in svg and "velocity := 0.1" in svg
    assert 'data-t0="0.0000"' in svg


def test_labels_are_escaped_and_long_runs_thinned() -> None:
    svg = speed_svg(SAMPLES, [(11.0, "<b>&</b>")])
    assert "&lt;b&gt;&amp;&lt;/b&gt;" in svg and "<b>" not in svg
    long = [(i * 0.01, 0.1) for i in range(20 * MAX_POINTS)]
    points = re.search(r'points="([^"]+)"', speed_svg(long, []))
    assert points is not None and len(points.group(1).split()) <= MAX_POINTS + 1


def test_no_samples_still_draws_axes() -> None:
    svg = speed_svg([], [(1.0, "x")])
    assert svg.startswith("<svg") and "polyline" not in svg and 'class="mark"' not in svg


def test_a_robot_rolling_back_slightly_shows_no_minus_zero() -> None:
    svg = speed_svg([(0.0, -0.01), (1.0, 0.2)], [])
    assert ">-0<" not in svg and ">0<" in svg
