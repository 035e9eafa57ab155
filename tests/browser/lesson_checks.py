"""What a lesson must show after it ran, read from the notebook's cells.

Each check returns the problems it found, in words (an empty list: all is well), so a walk can
record them all and go on.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from lab_ui import Cell

from course_lib.lessons.catalogue import LESSONS as CATALOGUE
from course_lib.lessons.catalogue import NUMBERS

__all__ = [
    "LESSONS",
    "PROBES",
    "WORLD_LESSONS",
    "cell_problems",
    "lesson_number",
    "run_problems",
]

# Every lesson's notebook, in order, and the lessons whose cells start (or attach to) the lab's
# world: both from the lesson catalogue (course_lib/lessons/catalogue), never a list of their own.
LESSONS = [spec.notebook for spec in CATALOGUE]
WORLD_LESSONS = tuple(spec.number for spec in CATALOGUE if spec.world)
SELF_CHECK = "lesson.self_check()"
PASSED = "Everything passed"
# The figures a full run prints, by lesson: (the cell's source, its last one with it, the text).
FIGURES: dict[int, list[tuple[str, str]]] = {
    7: [("lesson.drive_for(3.0)", "/odom says 0.20 m/s; the robot drove 0.6 m")],
    11: [("travel.check()", "passed!")],
}
# A cell a walk adds to a lesson once (as a learner adds one) to print a figure the lesson keeps:
# lesson 7's plot sees simulated time go back only if the lab's world restarts or a second one
# publishes /clock, and marks its own node's two velocity changes (0.2, then 0.0): `plot.still()`
# ends the live plot before the exercise's changes.
PROBES: dict[int, tuple[str, str]] = {
    7: (
        "print('time jumps:', plot.time_jumps, '| marks:', len(plot.marks))",
        "time jumps: 0 | marks: 2",
    ),
}
assert set(FIGURES) | set(PROBES) <= set(NUMBERS), "a figure or probe of no lesson in the table"
# How a course error reads in a cell (stderr, no traceback): "CourseError: ...".
_COURSE_ERROR = re.compile(r"^[A-Z]\w*Error: .*$", re.M)


def lesson_number(name: str) -> int:
    """Return the lesson number of a lesson file name ("07_move_the_robot.ipynb" -> 7)."""
    return int(name.split("_", 1)[0])


def cell_problems(name: str, cell: Cell) -> list[str]:
    """Return the errors one cell of lesson `name` shows (a traceback or a course error)."""
    where = f"{name}, cell `{cell.first_line()}`"
    problems = []
    for output in cell.outputs:
        if output.get("output_type") == "error":
            trace = "\n".join(output.get("traceback", []))
            trace = re.sub(r"\x1b\[[0-9;]*m", "", trace)
            problems.append(
                f"{where} failed: {output.get('ename')}: {output.get('evalue')}\n{trace[-1500:]}"
            )
        elif output.get("name") == "stderr":
            error = _COURSE_ERROR.search("".join(output.get("text", "")))
            if error:
                problems.append(f"{where} says: {error[0]}")
    return problems


def run_problems(name: str, cells: Sequence[Cell]) -> list[str]:
    """Return what is wrong after lesson `name` ran in full (Run All or restart and Run All).

    Every code cell ran without an error, its self-check says "Everything passed", and its
    figures (lesson 7's speed and distance, lesson 11's exercise verdict) are right.
    """
    number = lesson_number(name)
    problems = [p for cell in cells for p in cell_problems(name, cell)]
    idle = [c.first_line() for c in cells if not c.ran and c.source.strip()]
    if idle:
        problems.append(f"{name}: {len(idle)} of {len(cells)} cells did not run: {idle[:5]}")
    checks = [c for c in cells if SELF_CHECK in c.source]
    if not checks:
        problems.append(f"{name} has no `{SELF_CHECK}` cell")
    elif PASSED not in checks[-1].text:
        problems.append(f"{name}'s self-check did not pass:\n{checks[-1].text.strip()}")
    expected = FIGURES.get(number, [])
    if number in PROBES:
        expected = [*expected, PROBES[number]]
    for source, text in expected:
        shown = [c for c in cells if source in c.source]
        if not shown or text not in shown[-1].text:
            what = shown[-1].text.strip() if shown else "(no such cell)"
            problems.append(f"{name}: `{source}` should print {text!r}; it printed:\n{what}")
    return problems
