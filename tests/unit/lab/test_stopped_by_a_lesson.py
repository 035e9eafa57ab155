"""Which lesson stopped a node, read from the lab's parameter journal (issue 59): a `stopped`
record counts until the node, or its executable, is started again."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from course_lib.core import param_journal
from course_lib.lab.takeover import StoppedNode, stopped_by_a_lesson

DOMAIN = 229  # beyond the course's leases: no lab writes here
NODE = "/param_vel_node"
STOPPED = {"t": "stopped", "exe": "param_vel", "node": NODE, "started_by": "lesson 7",
           "by": "lesson 11", "for": "/descriptor_vel_node"}  # fmt: skip


@pytest.fixture(autouse=True)
def _clean() -> Iterator[None]:
    param_journal.journal_path(DOMAIN).unlink(missing_ok=True)
    yield
    param_journal.journal_path(DOMAIN).unlink(missing_ok=True)


def test_a_stopped_record_names_who_stopped_the_node_and_for_what() -> None:
    param_journal.append(DOMAIN, {"t": "named", "exe": "param_vel", "node": NODE})
    param_journal.append(DOMAIN, STOPPED)
    param_journal.append(DOMAIN, {"t": "named", "exe": "descriptor_vel", "node": "/other"})
    assert stopped_by_a_lesson(NODE, DOMAIN) == StoppedNode(
        NODE, "param_vel", "lesson 7", "lesson 11", "/descriptor_vel_node"
    )


@pytest.mark.parametrize(
    "later",
    [
        {"t": "named", "exe": "param_vel", "node": NODE},  # a lesson started it again
        {"t": "start", "exe": "param_vel", "args": [], "pid": 5},  # a terminal's ros2 run
    ],
)
def test_a_start_since_the_stop_means_the_records_cannot_tell(later: dict) -> None:  # type: ignore[type-arg]
    param_journal.append(DOMAIN, STOPPED)
    param_journal.append(DOMAIN, later)
    assert stopped_by_a_lesson(NODE, DOMAIN) is None


def test_no_record_or_no_domain_tells_nothing() -> None:
    assert stopped_by_a_lesson(NODE, DOMAIN) is None
    param_journal.append(DOMAIN, STOPPED)
    assert stopped_by_a_lesson("/other_node", DOMAIN) is None
    assert stopped_by_a_lesson(NODE, None) is None
