"""Launches from Python (the notebook API): parameters read back over real services."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from rcl_interfaces.srv import GetParameters

from course_lib.core.waiting import wait_until
from course_lib.launch import dry_run, launch
from course_lib.ros2.node.client import RosClient
from course_lib.session.session import Session

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _get(session: Session, node: str, name: str) -> object:
    client = session.node.create_client(GetParameters, f"{node}/get_parameters")
    try:
        assert client.wait_for_service(timeout_sec=15.0), f"{node} did not come up"
    finally:
        session.node.destroy_client(client)
    return RosClient(session.node, session.wait_future).get_parameters(node, [name])[0].value


@pytest.mark.parametrize(
    "args,node,expected",
    [
        (("param_vel.launch.py",), "/param_vel_node", 0.2),
        (("param_vel_file.launch.yaml",), "/param_vel_node", 0.4),
        (("param_vel.launch.xml", "velocity:=0.7"), "/param_vel_node", 0.7),
        (("param_vel_file.launch.xml",), "/robot/param_vel_node", 0.3),
        (("args.launch.py", "velocity:=0.5", "node_name:=vel"), "/vel", 0.5),
    ],
)
def test_parameters_reach_the_node(
    launch_session: Session,
    launch_env: dict[str, str],
    args: tuple[str, ...],
    node: str,
    expected: float,
) -> None:
    handle = launch("parameter_tests", *args, session=launch_session, env=launch_env)
    try:
        assert _get(launch_session, node, "velocity") == expected
    finally:
        code = handle.stop()
    assert code == 0
    assert "[WARNING] [launch]: user interrupted with ctrl-c (SIGINT)" in handle.output
    pid = int(handle.wait_for(r"process started with pid", 1.0).split("[")[-1].rstrip("]"))
    assert not os.path.exists(f"/proc/{pid}")


def test_a_notebook_launch_is_no_node_starting_but_its_nodes_are(
    launch_session: Session, launch_env: dict[str, str]
) -> None:
    """A command run moments after `%ros2 launch` waits for the nodes the launch starts, not
    for the launch's own process, which never joins DDS (it held every command for seconds,
    until it was 6 s old)."""
    from course_lib.ros2.node.participants import domain_newcomers

    handle = launch(
        "parameter_tests", "param_vel.launch.py", session=launch_session, env=launch_env
    )
    try:
        started = handle.wait_for(r"process started with pid", 15.0)
        assert started, handle.output
        node_pid = int(started.split("[")[-1].rstrip("]"))
        # the fixture's executables are sh wrappers: the node is a newcomer once they exec it
        # (ci119: checked while the wrapper still ran, which counts as a shell)
        assert wait_until(
            lambda: node_pid in domain_newcomers(launch_session.domain_id, joined=True), 5
        )
        assert handle.pid not in domain_newcomers(launch_session.domain_id, joined=True)
    finally:
        handle.stop()


def test_a_dying_process_leaves_the_others_running(
    launch_session: Session, launch_env: dict[str, str]
) -> None:
    handle = launch(
        "parameter_tests", "one_dies.launch.py", session=launch_session, env=launch_env
    )
    try:
        assert handle.wait_for(
            r"\[ERROR\] \[quitter-2\]: process has died \[pid \d+, "
            r"exit code 3, cmd 'sh -c exit 3'\]\.$",
            15.0,
        )
        assert _get(launch_session, "/param_vel_node", "velocity") == 0.0
    finally:
        handle.stop()


def test_syntax_error_is_reported_like_launch(
    launch_session: Session, launch_env: dict[str, str]
) -> None:
    handle = launch(
        "parameter_tests", "syntax_error.launch.py", session=launch_session, env=launch_env
    )
    assert handle.wait(20.0) == 1
    first = (
        "[ERROR] [launch]: Caught exception in launch (see debug for traceback): Caught "
        "multiple exceptions when trying to load file of format [py]:"
    )
    # stdout and stderr are read by two threads: find the error block, don't count lines.
    start = handle.output.index(first)
    assert handle.output[start : start + 3] == [
        first,
        " - SyntaxError: expected ':' (syntax_error.launch.py, line 4)",
        " - InvalidFrontendLaunchFileError: The launch file may have a syntax error, or its "
        "format is unknown",
    ]


def test_dry_run_warns_about_the_traps(fixture_prefix: Path, monkeypatch) -> None:
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(fixture_prefix))
    report = dry_run("parameter_tests", "traps.launch.py")
    assert report.nodes[0].values["velocity"] == (1, "the launch file's parameters dict")
    text = report.render()
    assert "key '/param_vel' matches no node of this launch" in text
    assert "'velocity' is declared double" in text and "Write 1.0." in text
