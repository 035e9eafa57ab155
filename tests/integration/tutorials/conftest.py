"""Fixtures of the tutorial tests: a course session, its daemon, a learner's home and terminals."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from learner_shell import LearnerShell
from ros2_golden import daemon, ros_session

__all__ = ["daemon", "ros_session"]


@pytest.fixture
def terminals(ros_session, daemon, tmp_path: Path) -> Iterator[Callable[[], LearnerShell]]:
    """Open lab terminals in a fresh home (cwd = home); all are closed at the end."""
    home = tmp_path / "home"
    home.mkdir()
    env = {**ros_session.env, "HOME": str(home)}
    # the test runner's own setting; with it, setuptools warns on stderr in every colcon build
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    opened: list[LearnerShell] = []

    def open_terminal() -> LearnerShell:
        shell = LearnerShell(env, home)
        opened.append(shell)
        return shell

    yield open_terminal
    for shell in opened:
        shell.close()
