"""The instructor's page (pure HTML): a row per learner, a column per lesson, all escaped."""

from __future__ import annotations

from datetime import UTC, datetime

from course_lib.hub.progress.page import render_page, rows_of
from course_lib.hub.progress.store import LessonState

T0 = datetime(2026, 11, 23, 19, 5, tzinfo=UTC)
TITLES = {n: f"Lesson {n}" for n in range(1, 12)}


def _state(user: str, lesson: int, passed: bool, failed: str = "") -> LessonState:
    return LessonState(user, lesson, passed, T0 if passed else None, failed,
                       None if passed else T0)  # fmt: skip


def test_no_learners_says_so() -> None:
    html = render_page([], [], titles=TITLES)
    assert "No learners yet." in html and '<td class="passed"' not in html


def test_each_learner_has_a_row_and_eleven_cells() -> None:
    states = [_state("alice", 7, True), _state("dave", 2, False, "The node runs")]
    html = render_page(["carol", "alice"], states, titles=TITLES)
    assert rows_of(["carol", "alice"], states) == ["alice", "carol", "dave"]
    rows = html.split("<tr>")[2:]  # after the header row
    assert [r.split("</td>")[0] for r in rows] == [
        '<td class="learner">alice', '<td class="learner">carol', '<td class="learner">dave'
    ]  # fmt: skip
    assert all(r.count("<td") == 12 for r in rows)
    assert '✓ passed<span class="when">2026-11-23 19:05 UTC</span>' in rows[0]
    assert rows[1].count('class="empty"') == 11
    assert "✗ failed" in rows[2] and "The node runs" in rows[2]


def test_everything_is_escaped() -> None:
    evil = '<script>alert("x")</script>'
    html = render_page([evil], [_state(evil, 3, False, f"{evil} & more")],
                       titles={**TITLES, 3: evil}, note=evil)  # fmt: skip
    assert "<script>alert" not in html  # the page's own script (its refresh) is the only one
    assert html.count("<script>") == 1
    assert "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; more" in html


def test_a_failure_after_a_pass_says_when_it_passed() -> None:
    state = LessonState("alice", 7, False, T0, "Speed is 0.2", T0)
    html = render_page(["alice"], [state], titles=TITLES)
    assert "(passed 2026-11-23 19:05 UTC)" in html and "Speed is 0.2" in html
