"""What a lab's parameter history knows without a lesson's help.

The lab's `ros2` daemon journals /parameter_events as the kernels do: a change made by another
node (or the node itself) while every notebook was closed is in `lesson.history` afterwards.
A node that only a terminal's `ros2 run` started (its log goes to the terminal) is named from
the graph: its start and its params file are in the history.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from param_setter import another_node_sets_velocity

from course_lib.core.param_journal import journal_path, read_journal
from course_lib.core.paths import REPO_ROOT
from course_lib.core.waiting import wait_until
from course_lib.notebook.history import OTHER, build_history, node_history
from course_lib.processes.ownership import LAB_ENV
from course_lib.ros2.command.daemon import start_daemon
from course_lib.session.session import Session, get_session

pytestmark = [pytest.mark.ros, pytest.mark.slow]

NODE = "/param_vel_node"


@pytest.fixture
def quiet_lab() -> Iterator[Session]:
    """A lab's domain whose daemon runs and where no kernel listens to /parameter_events."""
    session = Session()  # its node never subscribes to /parameter_events (no lesson starts)
    journal_path(session.domain_id).unlink(missing_ok=True)
    daemon = start_daemon({**session.env, LAB_ENV: "1"})
    try:
        yield session
    finally:
        daemon.stop()
        session.close()
        journal_path(session.domain_id).unlink(missing_ok=True)


def test_a_change_while_no_kernel_listens_is_in_the_history(quiet_lab: Session) -> None:
    node = quiet_lab.node
    assert wait_until(lambda: node.count_subscribers("/parameter_events") >= 1, 15.0), (
        "the lab's daemon does not listen to /parameter_events"
    )
    quiet_lab.run("parameter_tests", "param_vel")
    # the node's declarations go out before anyone matched its publisher (events are
    # volatile): a change made once the node is known is what the daemon must hear
    listed = lambda: NODE in {f"/{name}" for name in node.get_node_names()}  # noqa: E731
    assert wait_until(listed, 15.0), "the node never joined the graph"
    another_node_sets_velocity(quiet_lab.env, 0.3)

    def entries() -> list:
        return list(build_history(read_journal(quiet_lab.domain_id), NODE).entries)

    assert wait_until(entries, 10.0), "the change is not in the history"
    assert [(e.new.value, e.source) for e in entries()] == [(0.3, OTHER)]


def test_a_node_only_a_terminal_started_has_its_start_traced(tmp_path: Path) -> None:
    session = get_session()  # the kernel's: `lesson.history` reads the graph through it
    journal_path(session.domain_id).unlink(missing_ok=True)  # no lesson ever ran param_vel
    params = tmp_path / "terminal.yaml"
    params.write_text("/**:\n  ros__parameters:\n    velocity: 0.06\n")
    command = ["run", "parameter_tests", "param_vel", "--ros-args", "--params-file"]
    terminal = subprocess.Popen(
        [sys.executable, "-m", "course_lib.ros2.command.cli", *command, str(params)],
        env={**session.env, "PYTHONPATH": str(REPO_ROOT)},
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        start_new_session=True,  # Ctrl-C in a terminal reaches its whole process group
    )  # fmt: skip
    try:
        node = session.node
        listed = lambda: NODE in {f"/{name}" for name in node.get_node_names()}  # noqa: E731
        assert wait_until(listed, 15.0), "the node never joined the graph"

        def started() -> object:
            history = node_history(NODE, session.domain_id)
            return history if history.entries else None

        history = wait_until(started, 10.0)
        assert history is not None, "the terminal's start is not in the history"
        assert [(e.new.value, e.source) for e in history.entries] == [
            (0.06, "params file terminal.yaml")
        ]
        assert history.start_door == "terminal ros2"
    finally:
        os.killpg(terminal.pid, signal.SIGINT)
        terminal.wait(15)
        journal_path(session.domain_id).unlink(missing_ok=True)
