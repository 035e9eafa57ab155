"""A command's stderr in a notebook: a log line coloured by its severity ([INFO] never in an
error's red), anything else red; the text itself exactly what the command wrote."""

from __future__ import annotations

import html
import re

from course_lib.notebook.magics import ERROR_COLOUR, stderr_html

LOG = (
    "[INFO] [1700000000.1] [param_vel_node]: Velocity parameter is: 0.000000\n"
    "[param_vel-1] [INFO] [1700000000.2] [param_vel_node]: Velocity parameter is: 0.2\n"
    "[WARN] [1700000000.3] [param_vel_node]: slow\n"
    "[ERROR] [1700000000.4] [param_vel_node]: broken\n"
    "Traceback (most recent call last):\n"
    "Setting parameter failed: <out of range>\n"
)


def _runs(shown: str) -> list[tuple[str, str]]:
    """Return (colour, text) for each run of the <pre>: '' for the text's own colour."""
    body = re.fullmatch(r'<pre class="stderr" style="[^"]*">(.*)</pre>', shown, re.S)
    assert body is not None, shown
    parts = re.split(r'(<span style="color:#[0-9a-f]{6}">.*?</span>)', body[1], flags=re.S)
    runs = []
    for part in filter(None, parts):
        coloured = re.fullmatch(r'<span style="color:(#[0-9a-f]{6})">(.*)</span>', part, re.S)
        runs.append((coloured[1], coloured[2]) if coloured else ("", part))
    return runs


def test_info_lines_are_not_red_and_failures_are() -> None:
    runs = _runs(stderr_html(LOG))
    assert [colour for colour, _ in runs] == ["", "#8a4b00", ERROR_COLOUR]
    assert runs[0][1].count("[INFO]") == 2
    assert runs[2][1].startswith("[ERROR]") and "Setting parameter failed" in runs[2][1]


def test_the_text_is_unchanged() -> None:
    text = re.sub(r"<[^>]+>", "", stderr_html(LOG))
    assert html.unescape(text) == LOG
    assert stderr_html("no newline at the end").endswith("no newline at the end</span></pre>")
