"""Fixtures shared by the whole suite, and the order in which its files are handed out."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from course_lib.session.session import Session

# The longest files, longest first (seconds in a full run on 2 cores, 2026-11). `make test`
# hands whole files to its two workers in collection order (`--dist loadfile
# --no-loadscope-reorder`): a long file handed out last keeps one worker busy while the other
# has nothing left, so the long ones go first and the short ones fill in around them.
LONGEST_FIRST = (
    "test_lab_full_walk.py",  # 220
    "test_second_configuration.py",  # 70
    "test_hub_attacks_own_network.py",  # 71
    "test_replay_lab_browser.py",  # 70
    "test_ros2_first_call.py",  # 65
    "test_lab_random_walk.py",  # 65
    # 140; not first: the learners' environment it needs is built meanwhile (browser/conftest)
    "test_class_hub.py",
    "test_skill_exercises.py",  # 70
    "test_lab_lessons_browser.py",  # 60
)


def _hand_out_rank(item: pytest.Item) -> tuple[int, int]:
    name = item.path.name
    if name in LONGEST_FIRST:
        return (0, LONGEST_FIRST.index(name))
    if "browser" in item.keywords:
        return (1, 0)
    return (2, 0) if "slow" in item.keywords else (3, 0)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Put the longest files first (a stable sort: each file's tests keep their order)."""
    items.sort(key=_hand_out_rank)


@pytest.fixture(scope="module")
def session() -> Iterator[Session]:
    """Yield a course session with its own ROS domain for one test module."""
    course_session = Session()
    try:
        yield course_session
    finally:
        course_session.close()
