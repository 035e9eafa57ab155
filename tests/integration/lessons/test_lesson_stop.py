"""`lesson.stop(name)` says how a node ended; one that fails on Ctrl-C shows its last lines.

A node that ended with exit code 1 when the lesson stopped it said only "exit code 1" (seen
once in a CI run of lesson 11, with nothing to tell why): a terminal would have shown the
traceback, and so does the lesson now.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator

import pytest

from course_lib.config.course import load_course_settings
from course_lib.lessons import Lesson
from course_lib.session.session import get_session

pytestmark = [pytest.mark.ros]

# a program that fails when Ctrl-C reaches it, as a node whose shutdown raises does
FAILS_ON_CTRL_C = """
import time
try:  # "Ready" inside: a Ctrl-C right after it still lands in the try
    print("Ready", flush=True)
    time.sleep(60)
except KeyboardInterrupt:
    raise RuntimeError("publisher's context is invalid") from None
"""
QUITS_ON_CTRL_C = """
import time
try:  # "Ready" inside: a Ctrl-C right after it still lands in the try
    print("Ready", flush=True)
    time.sleep(60)
except KeyboardInterrupt:
    pass
"""


@pytest.fixture(scope="module")
def lesson() -> Iterator[Lesson]:
    session = get_session()
    yield Lesson(11, session, load_course_settings())
    session.close()


def _start(lesson: Lesson, name: str, program: str) -> None:
    child = lesson.session.spawn([sys.executable, "-c", program], name=name)
    assert child.wait_for_line("Ready", 30.0) is not None


def test_a_node_that_fails_on_ctrl_c_shows_its_last_lines(lesson: Lesson) -> None:
    _start(lesson, "failing_node", FAILS_ON_CTRL_C)
    said = repr(lesson.stop("failing_node")).splitlines()
    assert said[:2] == ["failing_node stopped (Ctrl-C), exit code 1.", "Its last lines:"], said
    assert said[-1] == "  RuntimeError: publisher's context is invalid", said


def test_a_node_that_quits_on_ctrl_c_says_exit_code_0_only(lesson: Lesson) -> None:
    _start(lesson, "quitting_node", QUITS_ON_CTRL_C)
    assert repr(lesson.stop("quitting_node")) == "quitting_node stopped (Ctrl-C), exit code 0.\n"
