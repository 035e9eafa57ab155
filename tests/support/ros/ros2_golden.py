"""Helpers and fixtures for the `ros2` golden tests: a session, the golden nodes, both doors."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.core.waiting import wait_until
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import Session, get_session

GOLDEN = Path(__file__).resolve().parents[2] / "golden" / "ros2"
TYPES_DEFAULTS = {
    "count": 5,
    "robot_name": "turtle",
    "flags": [True, False, True],
    "gains": [0.5, 1.0, 2.5],
    "names": ["left", "right"],
    "max_speed": 1.0,
    "retries": 3,
    "pid.kp": 1.0,
    "pid.ki": 0.1,
}


def golden_cases() -> dict[str, dict]:
    """Return the golden cases by name."""
    return {c["case"]: c for c in json.loads((GOLDEN / "cases.json").read_text())}


def start_node(session: Session, script: str, node: str):  # type: ignore[no-untyped-def]
    """Start a golden node and wait until its parameter services answer."""
    child = session.spawn([sys.executable, str(GOLDEN / "nodes" / script)], name=node)
    assert api.client().wait_for_node(f"/{node}", include_hidden=False, timeout=10)
    assert api.client().services_ready(f"/{node}", timeout=10)
    return child


@pytest.fixture(scope="module")
def ros_session() -> Iterator[Session]:
    """Yield this module's session (closed afterwards: nodes and daemon stop)."""
    session = get_session()
    yield session
    session.close()


@pytest.fixture(scope="module")
def daemon(ros_session: Session) -> Iterator[None]:
    """Start the terminal commands' daemon for the session's domain."""
    from course_lib.ros2 import start_daemon
    from course_lib.ros2.node.connect import daemon_socket

    child = start_daemon(ros_session.env)
    assert wait_until(lambda: os.path.exists(daemon_socket(ros_session.domain_id)), 15)
    yield
    child.stop()


def run_console(env: dict[str, str], command: str) -> tuple[str, str, int]:
    """Run a golden command line through the `ros2` console entry point."""
    import shlex

    argv = shlex.split(command)[1:]
    proc = subprocess.run(
        [sys.executable, "-m", "course_lib.ros2.command.cli", *argv],
        cwd=GOLDEN,
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    return proc.stdout, proc.stderr, proc.returncode


def run_api(command: str) -> tuple[str, str, int]:
    """Run a golden command line through the in-process Python door."""
    out = api.ros2(command, cwd=str(GOLDEN))
    return out.stdout, out.stderr, out.exit_code


def reset_parameters(nodes: set[str]) -> None:
    """Put the golden nodes' parameters back to their start values."""
    if "param_vel_node" in nodes:
        assert api.param_set("/param_vel_node", "velocity", 0.0).successful
    if "param_types_node" in nodes:
        for name, value in TYPES_DEFAULTS.items():
            assert api.param_set("/param_types_node", name, value).successful


def traceback_summary(stderr: str) -> tuple[str, str]:
    """Return a traceback's first line and its exception lines (frames left out)."""
    lines = stderr.splitlines()
    tail = [i for i, line in enumerate(lines) if i and not line.startswith(" ")]
    return lines[0], "\n".join(lines[tail[0] :]) if tail else ""


def console_env(session: Session) -> dict[str, str]:
    """Return the environment a JupyterLab terminal of this session has."""
    return {**session.env, "PYTHONPATH": str(GOLDEN.parents[2]), "COLUMNS": "80"}


def compare(case: dict, got: tuple[str, str, int]) -> None:
    """Assert that output matches a golden case (tracebacks: first and exception lines)."""
    stdout, stderr, code = got
    assert (stdout, code) == (case["stdout"], case["exit"])
    if case["stderr"].startswith("Traceback"):
        assert traceback_summary(stderr) == traceback_summary(case["stderr"])
    else:
        assert stderr == case["stderr"]
