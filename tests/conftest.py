"""Fixtures shared by the whole suite."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from course_lib.session.session import Session


@pytest.fixture(scope="module")
def session() -> Iterator[Session]:
    """Yield a course session with its own ROS domain for one test module."""
    course_session = Session()
    try:
        yield course_session
    finally:
        course_session.close()
