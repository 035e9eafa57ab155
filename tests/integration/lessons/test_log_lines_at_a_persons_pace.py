"""Lesson 5's "next five lines" of the tutorial's node, asked after a person's reading.

Past a node's first seconds its lines are read a few at a time (processes/output_lines.py):
the lines the cell shows must still be consecutive ticks (none lost, none twice), the first
printed at most half a second before the cell ran, and the answer must come within about
what the ticks themselves take.
"""

from __future__ import annotations

import itertools
import re
import time
from collections.abc import Iterator

import pytest

from course_lib.config.course import load_course_settings
from course_lib.lessons import Lesson
from course_lib.processes.output_lines import PROMPT_S
from course_lib.session.session import get_session

pytestmark = [pytest.mark.ros]

TICK = re.compile(r"\[INFO\] \[(\d+\.\d+)\] \[param_vel_node\]: Velocity parameter is")
TICK_S = 0.1  # the node's timer
OLDEST_S = 0.5  # how old the first of the "next" lines may be when the cell runs


@pytest.fixture(scope="module")
def lesson() -> Iterator[Lesson]:
    session = get_session()
    yield Lesson(5, session, load_course_settings())
    session.close()


def test_the_next_lines_after_a_minute_of_reading_are_consecutive_ticks(lesson: Lesson) -> None:
    lesson.run("parameter_tests", "param_vel")
    try:
        time.sleep(PROMPT_S + 2.0)  # the learner reads the lesson's text: the node talks on
        asked = time.time()
        lines = lesson.log_lines("param_vel", 5).lines
        took = time.time() - asked
        stamps = [float(TICK.search(line).group(1)) for line in lines]  # type: ignore[union-attr]
        gaps = [round(b - a, 2) for a, b in itertools.pairwise(stamps)]
        assert len(stamps) == 5 and all(0.05 < gap < 0.2 for gap in gaps), (lines, gaps)
        assert stamps[0] > asked - OLDEST_S, (stamps[0] - asked, lines)
        assert took < 5 * TICK_S + 1.0, f"log_lines took {took:.2f} s"
    finally:
        lesson.stop("param_vel")
