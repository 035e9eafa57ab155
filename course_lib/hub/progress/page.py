"""The instructor's progress page as HTML (pure: data in, text out; everything escaped)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from datetime import datetime
from html import escape

from . import LESSONS
from .store import ExerciseStats, LessonState

__all__ = ["render_error", "render_page", "rows_of"]

_STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; }
th, td { border: 1px solid #ccc; padding: 0.3em 0.5em; vertical-align: top; }
th { background: #f4f4f4; }
td.passed { background: #e6f4ea; }
td.failed { background: #fdecea; }
td.learner { font-weight: bold; }
.when { display: block; font-size: 0.8em; color: #555; }
.what { display: block; font-size: 0.85em; max-width: 14em; }
.note { color: #8a4b00; }
"""

# A page that reloads itself on a timer must let its reader stop it (WCAG 2.2.1; axe's
# meta-refresh): a box, ticked, reloads every 30 s; unticked, never.
_REFRESH = """<label><input type="checkbox" id="refresh" checked> Refresh every 30 seconds</label>
<script>(function () {
  var box = document.getElementById("refresh"), timer = null;
  function arm() {
    clearTimeout(timer);
    if (box.checked) timer = setTimeout(function () { location.reload(); }, 30000);
  }
  box.addEventListener("change", arm);
  arm();
})();</script>"""


def _when(moment: datetime | None) -> str:
    return moment.strftime("%Y-%m-%d %H:%M UTC") if moment else ""


def _cell(state: LessonState | None) -> str:
    if state is None:
        return '<td class="empty"></td>'
    if state.passed:
        when = _when(state.passed_at)
        return f'<td class="passed">✓ passed<span class="when">{escape(when)}</span></td>'
    what = escape(state.failed or "a check failed")
    earlier = f" (passed {_when(state.passed_at)})" if state.passed_at else ""
    return (
        f'<td class="failed" title="{what}">✗ failed<span class="what">{what}</span>'
        f'<span class="when">{escape(_when(state.failed_at) + earlier)}</span></td>'
    )


def _exercises_table(stats: Iterable[ExerciseStats]) -> str:
    rows = "".join(
        f'<tr><td>{s.lesson}</td><td class="exercise">{escape(s.exercise)}</td>'
        f'<td class="rate">{s.pass_rate * 100:.0f} %</td><td>{s.passed} of {s.tried}</td>'
        f'<td class="median">{"–" if s.median_attempts is None else f"{s.median_attempts:g}"}'
        "</td></tr>"
        for s in stats
    )
    if not rows:
        return "<h2>Exercises</h2><p>No exercise attempts yet.</p>"
    return (
        "<h2>Exercises</h2><p>Each exercise's check across the class: the share of learners "
        "who tried it and passed, and the median number of attempts it took them.</p>"
        "<table><thead><tr><th>Lesson</th><th>Exercise</th><th>Pass rate</th><th>Passed</th>"
        f"<th>Median attempts to pass</th></tr></thead><tbody>{rows}</tbody></table>"
    )


def rows_of(learners: Iterable[str], states: Iterable[LessonState]) -> list[str]:
    """Return the page's row names: every learner, plus anyone with records, sorted."""
    return sorted(set(learners) | {s.user for s in states})


def render_page(
    learners: Iterable[str],
    states: Iterable[LessonState],
    *,
    titles: Mapping[int, str],
    note: str = "",
    exercises: Iterable[ExerciseStats] = (),
) -> str:
    """Return the page: one row per learner, one column per lesson, a note above if any."""
    states = list(states)
    by_key = {(s.user, s.lesson): s for s in states}
    names = rows_of(learners, states)
    head = "".join(
        f'<th title="{escape(titles.get(n, ""))}">{n}<br><small>{escape(titles.get(n, ""))}'
        "</small></th>"
        for n in LESSONS
    )
    body = "".join(
        f'<tr><td class="learner">{escape(name)}</td>'
        + "".join(_cell(by_key.get((name, n))) for n in LESSONS)
        + "</tr>"
        for name in names
    )
    if not names:
        body = f'<tr><td colspan="{len(LESSONS) + 1}">No learners yet.</td></tr>'
    note_html = f'<p class="note">{escape(note)}</p>' if note else ""
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>Course progress</title><style>{_STYLE}</style></head><body>"
        "<h1>Course progress</h1>"
        f"<p>{len(names)} learner(s). Each cell is the lesson's latest self-check. "
        f"{_REFRESH}</p>"
        f"{note_html}"
        f"<table><thead><tr><th>Learner</th>{head}</tr></thead><tbody>{body}</tbody></table>"
        f"{_exercises_table(exercises)}"
        "</body></html>\n"
    )


def render_error(status_code: int, message: str) -> str:
    """Return the service's error page: its status and what went wrong, in English."""
    return (
        f'<!DOCTYPE html><html lang="en"><head><title>{status_code}</title></head><body>'
        f"<h1>{status_code}: {escape(message)}</h1></body></html>\n"
    )
