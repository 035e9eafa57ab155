"""The parameter history of one lab seen from several real kernels, across a kernel restart."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from jupyter_kernels import Kernel
from suite_env import independent_env

from course_lib.core.param_journal import journal_path
from course_lib.processes.domain import DOMAIN_ENV, lease_domain

pytestmark = [pytest.mark.ros, pytest.mark.slow]

START = "from course_lib.lessons import start\nlesson = start({})"


@pytest.fixture
def lab_env() -> Iterator[dict[str, str]]:
    """Yield the environment of a lab's kernels: one shared ROS domain."""
    lease = lease_domain({})
    journal_path(lease.domain_id).unlink(missing_ok=True)
    yield independent_env(**{DOMAIN_ENV: str(lease.domain_id)})
    journal_path(lease.domain_id).unlink(missing_ok=True)
    lease.release()


def test_history_survives_a_kernel_restart(lab_env: dict[str, str]) -> None:
    owner = Kernel(lab_env)  # lesson 5's notebook: it runs the node
    other = Kernel(lab_env)  # lesson 7's notebook: it sets the parameter, then restarts
    try:
        owner.ok(START.format(5))
        owner.ok("%ros2 run parameter_tests param_vel --ros-args -p velocity:=0.04")
        other.ok(START.format(7))
        assert (
            "Set parameter successful"
            in other.ok("%ros2 param set /param_vel_node velocity 0.11").text
        )
        other.shutdown()
        other = Kernel(lab_env)
        other.ok(START.format(7))
        text = other.ok("lesson.history()").text
        assert "since it started (%ros2 magic)" in text
        assert "#1  velocity  — → 0.04     -p at start (%ros2 magic)" in text
        assert "#2  velocity  0.04 → 0.11  %ros2 magic" in text
        reset = other.ok("lesson.reset()").text
        assert "velocity: 0.11 → 0.04" in reset
        assert "Double value is: 0.04" in other.ok("%ros2 param get /param_vel_node velocity").text
    finally:
        other.shutdown()
        owner.shutdown()
