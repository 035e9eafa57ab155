"""The speed plot in words (its SVG's description): each marked change and what the speed did."""

from __future__ import annotations

from course_lib.notebook.widgets.speed_summary import speed_summary
from course_lib.viz.speed_svg import speed_svg

# 0.0 m/s until 12.0 s, then a ramp to 0.2 m/s reached at 12.4 s, back to 0.0 from 15.0 s
SAMPLES = [(10.0 + i * 0.1, min(max(0.0, (i - 20) * 0.05), 0.2)) for i in range(50)]
SAMPLES += [(15.0 + i * 0.1, max(0.0, 0.2 - i * 0.05)) for i in range(1, 20)]
MARKS = [(12.0, "#1 velocity := 0.2"), (15.0, "#2 velocity := 0")]


def test_each_change_says_what_the_speed_did_and_when() -> None:
    said = speed_summary(SAMPLES, MARKS)
    assert said == (
        "Simulated time 10.0 to 16.9 s. "
        "velocity was set to 0.2 at 12.0 s: speed rose from 0.00 to 0.20 m/s by 12.4 s. "
        "velocity was set to 0 at 15.0 s: speed fell from 0.20 to 0.00 m/s by 15.4 s. "
        "Top speed 0.20 m/s; last 0.00 m/s."
    )


def test_a_change_that_moved_nothing_says_the_speed_stayed() -> None:
    still = [(float(t), 0.0) for t in range(5)]
    assert "velocity was set to 0.0 at 2.0 s: speed stayed at 0.00 m/s." in speed_summary(
        still, [(2.0, "velocity := 0.0")]
    )


def test_a_robot_standing_still_is_never_at_minus_zero() -> None:
    said = speed_summary([(0.0, -0.001), (1.0, 0.2)], [(0.5, "velocity := 0.2")])
    assert "from 0.00 to 0.20 m/s" in said and "-0.00" not in said


def test_without_marks_or_samples() -> None:
    assert speed_summary([], []) == "No speed sample yet."
    said = speed_summary([(0.0, 0.0), (1.0, 0.1)], [(5.0, "velocity := 1")])  # mark outside
    assert said == "Simulated time 0.0 to 1.0 s. Speed from 0.00 to 0.10 m/s. " + (
        "Top speed 0.10 m/s; last 0.10 m/s."
    )


def test_the_svg_is_a_picture_named_by_its_title_and_described_by_the_summary() -> None:
    svg = speed_svg(SAMPLES, MARKS, summary=speed_summary(SAMPLES, MARKS))
    assert 'role="img"' in svg.splitlines()[0]
    assert "<title>Robot speed from /odom</title>" in svg
    assert "<desc>Simulated time 10.0 to 16.9 s. velocity was set to 0.2" in svg
    assert "<desc>" not in speed_svg(SAMPLES, MARKS)  # the replay's, without a summary
