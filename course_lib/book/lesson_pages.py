"""A lesson notebook as its book page: stored outputs, plus what only a real run can show.

The page keeps the notebook's text, code and stored outputs (what nbval checks) and adds:
how to run the lesson; for a driving lesson, the 3D replay of a real run in place of the
live view's placeholder, its speed plot as a picture in place of the live plot's, and the
self-check's replay link pointing at that replay.
"""

from __future__ import annotations

import re
from typing import Any

from ..core.files.live_outputs import PLACEHOLDERS
from ..lessons.catalogue import LESSONS
from ..lessons.catalogue.spec import LessonSpec
from .recording import Recording

__all__ = ["REPLAYS_DIR", "lesson_page"]

REPLAYS_DIR = "_static/replays"  # in the book's sources and site
# the self-check's line on the learner's replay, as the notebook stores it (see ReplayLink)
_STORED_REPLAY = re.compile(
    r"Replay of this run, saved \(opens without a kernel\): "
    r'<a href="my_files/replays/lesson\d\d-[^"]*\.html"[^>]*>[^<]*</a>'
)
VIEW_CALL = "lesson.world()"
PLOT_CALL = "lesson.speed_plot()"
REPLAY_HEIGHT_PX = 760  # the 3D view, its controls and the speed plot at a desktop's width
SVG_NS = "http://www.w3.org/2000/svg"
# What a live output's stored placeholder says in the book, which runs nothing.
BOOK_PLACEHOLDERS = {
    PLACEHOLDERS["view"]: (
        "When you run this lesson, this cell shows the robot live in 3D, which you can turn "
        "and zoom. The book runs nothing: lessons "
        + ", ".join(str(spec.number) for spec in LESSONS if spec.driven_node)
        + " show a 3D replay of a real run instead."
    ),
    PLACEHOLDERS["widget"]: (
        "When you run this lesson, this cell shows a live widget that follows the running "
        "nodes. The book runs nothing, so it cannot show it here."
    ),
}


def _run_this_lesson(spec: LessonSpec) -> str:
    return (
        "```{admonition} Run this lesson\n"
        ":class: tip\n"
        "In a clone of the course, `make lab` opens JupyterLab on lesson 1; this lesson is "
        f"`notebooks/{spec.notebook}`. [Getting started](../guides/getting-started.md) says "
        "what it needs and what to do when something goes wrong. The outputs below are the "
        "ones stored with the notebook"
        + (
            "; the 3D replay and the speed plot were recorded from a real run of this lesson "
            "when this book was built."
            if spec.driven_node
            else "."
        )
        + "\n```"
    )


def _replay_output(spec: LessonSpec, recording: Recording) -> dict[str, Any]:
    src = f"../{REPLAYS_DIR}/{recording.replay.name}"
    title = f"Lesson {spec.number}: 3D replay of a real run, with its speed plot"
    frame = (
        f'<iframe class="course-replay" src="{src}" title="{title}" width="100%" '
        f'height="{REPLAY_HEIGHT_PX}" loading="lazy"></iframe>'
        f'<p><a href="{src}">Open the replay on its own page</a> (it plays offline).</p>'
    )
    return {
        "output_type": "display_data",
        "metadata": {},
        "data": {"text/html": frame, "text/plain": title},
    }


def _speed_output(spec: LessonSpec, recording: Recording) -> dict[str, Any]:
    svg = recording.speed.read_text(encoding="utf-8")
    if "xmlns=" not in svg.split(">", 1)[0]:  # drawn inline in a lab; an <img> needs it
        svg = svg.replace("<svg", f'<svg xmlns="{SVG_NS}"', 1)
    return {
        "output_type": "display_data",
        "metadata": {},
        "data": {
            "image/svg+xml": svg,
            "text/plain": f"Lesson {spec.number}'s speed plot (recorded run)",
        },
    }


def _for_readers(output: Any) -> None:
    """Reword a live output's placeholder ("run this cell") for a reader of the book."""
    data = output.get("data", {})
    text = data.get("text/plain")
    text = "".join(text) if isinstance(text, list) else text
    if text in BOOK_PLACEHOLDERS:
        data["text/plain"] = BOOK_PLACEHOLDERS[text]


def _relink(output: Any, recording: Recording | None) -> None:
    html = output.get("data", {}).get("text/html")
    if html is None:
        return
    text = "".join(html) if isinstance(html, list) else html
    if recording is None:
        link = "No replay of this lesson was recorded for this book."
    else:
        name = recording.replay.name
        href = f"../{REPLAYS_DIR}/{name}"
        link = f'Replay of a real run, recorded for this book: <a href="{href}">{name}</a>'
    output["data"]["text/html"] = _STORED_REPLAY.sub(link, text)


def lesson_page(nb: Any, spec: LessonSpec, recording: Recording | None) -> Any:
    """Edit lesson `spec`'s notebook `nb` (in place) into its book page; return it."""
    import nbformat

    nb.cells.insert(1, nbformat.v4.new_markdown_cell(_run_this_lesson(spec)))
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        cell.metadata.pop("tags", None)  # nbval's tags mean nothing to a reader
        if recording is not None and VIEW_CALL in cell.source:
            cell.outputs = [nbformat.from_dict(_replay_output(spec, recording))]
        elif recording is not None and PLOT_CALL in cell.source:
            cell.outputs = [nbformat.from_dict(_speed_output(spec, recording))]
            alt = f"Lesson {spec.number}: the robot's speed from /odom over a real run"
            cell.metadata["mystnb"] = {"image": {"alt": alt}}
        for output in cell.outputs:
            _for_readers(output)
            _relink(output, recording)
    return nb
