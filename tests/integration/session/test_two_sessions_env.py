"""A second session made and closed in the same process leaves the first one's domain in place.

A test module (or a script) may make a `Session()` of its own while the process's session
(`get_session()`) lives on. Closing the second one used to empty os.environ's ROS_DOMAIN_ID:
from then on `%ros2 run` recorded its start in no journal (the history lost the node's start)
and `!ros2 ...` went to domain 0.
"""

from __future__ import annotations

import os

import pytest

from course_lib.core.param_journal import journal_path, read_journal
from course_lib.core.waiting import wait_until
from course_lib.notebook.magics import run_line
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import Session, get_session

pytestmark = [pytest.mark.ros]


def test_closing_another_session_keeps_the_current_sessions_domain() -> None:
    current = get_session()
    other = Session()
    assert os.environ["ROS_DOMAIN_ID"] == str(other.domain_id)
    other.close()
    assert os.environ.get("ROS_DOMAIN_ID") == str(current.domain_id)

    journal_path(current.domain_id).unlink(missing_ok=True)
    try:
        assert "Velocity parameter is" in run_line("run parameter_tests param_vel").output.text
        assert wait_until(lambda: "/param_vel_node" in api.node_list(), 10.0)
        starts = [r for r in read_journal(current.domain_id) if r.get("t") == "start"]
        assert [(r["exe"], r["door"]) for r in starts] == [("param_vel", "%ros2")]
    finally:
        current.close()
