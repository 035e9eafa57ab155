"""Launch files in the style of the Jazzy launch tutorials, run by the `ros2 launch` command.

Event handlers, substitutions (Python, YAML and XML, included with arguments) and a large
project (groups with scoped parameters, namespaces and remaps); values are read back from the
nodes over their real parameter services, remaps from the real ROS graph.
"""

from __future__ import annotations

import os
import re
import signal
import time

import pytest
from rcl_interfaces.srv import GetParameters

from course_lib.ros2.node.client import RosClient
from course_lib.session.session import Session

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _velocity(session: Session, node: str) -> object:
    client = session.node.create_client(GetParameters, f"{node}/get_parameters")
    try:
        assert client.wait_for_service(timeout_sec=20.0), f"{node} did not come up"
    finally:
        session.node.destroy_client(client)
    client_ = RosClient(session.node, session.wait_future)
    return client_.get_parameters(node, ["velocity"])[0].value


def _publishers(session: Session, name: str, namespace: str = "/") -> set[str]:
    deadline = time.monotonic() + 20.0
    while time.monotonic() < deadline:
        try:
            found = session.node.get_publisher_names_and_types_by_node(name, namespace)
        except Exception:  # the node is not discovered yet
            found = []
        topics = {topic for topic, _types in found}
        if "/rosout" in topics and len(topics) > 2:
            return topics
        time.sleep(0.1)
    raise AssertionError(f"{namespace}/{name} was not discovered")


def _lines(data: bytes) -> list[str]:
    return data.decode().splitlines()


def test_event_handlers_tutorial(launch_session: Session, ros2_launch) -> None:
    run = ros2_launch(
        "parameter_tests",
        "example_event_handlers.launch.py",
        "use_provided_velocity:=True",
        "new_velocity:=0.25",
    )
    done = b"[INFO] [sim velocity 0.25-4]: process has finished cleanly"
    assert run.wait_for(done, timeout=40.0), run.stdout
    assert _velocity(launch_session, "/robot1/sim") == 0.25
    lines = _lines(run.stdout)
    wait = "python3 -c \"import time; time.sleep(0.5); print('velocity node is up')\"-2"
    expected_order = [
        "[INFO] [param_vel-1]: process started with pid [",
        "[INFO] [launch.user]: Velocity node started, waiting for it",
        f"[INFO] [{wait}]: process started with pid [",
        '[INFO] [launch.user]: Wait says "velocity node is up"',
        f"[INFO] [{wait}]: process has finished cleanly [pid ",
        "[INFO] [launch.user]: Wait finished",
        "[INFO] [sim use_sim_time false-3]: process started with pid [",
        "[INFO] [sim velocity 0.25-4]: process started with pid [",
    ]
    found = [next(i for i, line in enumerate(lines) if line.startswith(e)) for e in expected_order]
    assert found == sorted(found), lines
    # The tutorial closes turtlesim's window: here the node alone gets Ctrl-C.
    match = re.search(rb"\[param_vel-1\]: process started with pid \[(\d+)\]", run.stdout)
    assert match
    os.kill(int(match.group(1)), signal.SIGINT)
    assert run.finish() == 0
    tail = [line for line in _lines(run.stdout) if line.startswith("[INFO] [launch.user]")][-2:]
    assert tail == [
        "[INFO] [launch.user]: learner closed the velocity node",
        "[INFO] [launch.user]: Launch was asked to shutdown: Node closed",
    ]
    assert b"user interrupted" not in run.stdout


@pytest.mark.parametrize(
    "file,namespace",
    [
        ("example_main.launch.py", "/robot2"),
        ("example_main.launch.yaml", "/robot3"),
        ("example_main.launch.xml", "/robot4"),
    ],
)
def test_substitutions_tutorial(
    launch_session: Session, ros2_launch, file: str, namespace: str
) -> None:
    run = ros2_launch("parameter_tests", file)
    # echo, `ros2 param set` of use_sim_time, then the one the timer starts (condition true)
    assert run.wait_for(b"process has finished cleanly", count=3, timeout=40.0), run.stdout
    assert _velocity(launch_session, f"{namespace}/sim") == 0.25
    assert f"velocity node in {namespace[1:]}" in run.stdout.decode()
    assert b"velocity not provided" not in run.stdout
    run.interrupt_group()
    assert run.finish() == 0
    assert b"[WARNING] [launch]: user interrupted with ctrl-c (SIGINT)" in run.stdout


def test_unless_condition_and_defaults(launch_session: Session, ros2_launch) -> None:
    run = ros2_launch("parameter_tests", "example_substitutions.launch.py")
    done = b"[INFO] [sim use_sim_time false-4]: process has finished cleanly"
    assert run.wait_for(done, timeout=40.0), run.stdout
    assert _velocity(launch_session, "/robot1/sim") == 0.0
    assert b"[echo-3] velocity not provided" in run.stdout
    run.interrupt_group()
    assert run.finish() == 0


def test_large_project_tutorial(launch_session: Session, ros2_launch) -> None:
    run = ros2_launch("parameter_tests", "large_project.launch.py")
    assert run.wait_for(b"[INFO] [param_vel-9]: process started", timeout=30.0), run.stdout
    expected = {
        "/world2/sim": 0.15,  # PushROSNamespace around an include; `/**` params file
        "/world3/sim": 0.15,
        "/listener": 0.33,  # launch argument passed to the included file
        "/scoped": 0.12,  # SetParameter inside the group
        "/from_file/sim": 0.3,  # SetParametersFromFile inside the group
        "/mimic": 0.0,  # after the groups: nothing of theirs
        "/learner_fixed": 0.0,  # name from EnvironmentVariable('USER')
        "/xml/param_vel_node": 0.21,  # an XML file included with an argument, in a group
        "/yaml_world/sim": 0.15,  # a YAML file included with an argument
    }
    assert {node: _velocity(launch_session, node) for node in expected} == expected
    assert "/scoped_cmd_vel" in _publishers(launch_session, "scoped")
    mimic = _publishers(launch_session, "mimic")
    assert "/world2/sim/cmd_vel_mimic" in mimic and "/scoped_cmd_vel" not in mimic
    run.interrupt_group()
    assert run.finish() == 0
    # launch stops the processes newest first (each registered its shutdown handler first)
    order = re.findall(rb"\[param_vel-(\d)\]: sending signal 'SIGINT'", run.stdout)
    assert order == [str(n).encode() for n in range(9, 0, -1)]


def test_what_the_course_lacks_fails_in_one_line(ros2_launch) -> None:
    run = ros2_launch("parameter_tests", "composable.launch.py")
    assert run.finish() == 1
    errors = [line for line in _lines(run.stdout) if line.startswith("[ERROR]")]
    assert errors == [
        "[ERROR] [launch]: Caught exception in launch (see debug for traceback): "
        "'ComposableNodeContainer' of 'launch_ros.actions' is not available in this course; "
        "'launch_ros.actions' here has: Node, PushROSNamespace, PushRosNamespace, SetParameter, "
        "SetParametersFromFile, SetRemap"
    ]
    assert b"Traceback" not in run.stdout + run.stderr
    assert b"ImportError" not in run.stdout + run.stderr


def test_required_process_shuts_the_launch_down(ros2_launch) -> None:
    run = ros2_launch("parameter_tests", "required_process.launch.py")
    assert run.finish() == 0
    lines = [re.sub(r"pid (\[?)\d+", r"pid \1N", line) for line in _lines(run.stdout)]
    assert lines[2:] == [
        "[INFO] [launch.user]: fast mode",
        "[INFO] [launch.user]: not slow",
        "[INFO] [sleep-1]: process started with pid [N]",
        "[INFO] [echo-2]: process started with pid [N]",
        "[echo-2] hello",
        "[echo-2] ",
        "[INFO] [echo-2]: process has finished cleanly [pid N]",
        "[INFO] [launch]: process[echo-2] was required: shutting down launched system",
        "[INFO] [launch.user]: shutdown: worker done",
        "[INFO] [sleep-1]: sending signal 'SIGINT' to process[sleep-1]",
        "[ERROR] [sleep-1]: process has died [pid N, exit code -2, cmd 'sleep 60'].",
    ]
    assert run.stderr.decode().count("UserWarning: The 'LaunchConfigurationEquals' and") == 2


def test_launch_configuration_conditions_follow_arguments(ros2_launch) -> None:
    run = ros2_launch("parameter_tests", "required_process.launch.py", "mode:=slow")
    assert run.finish() == 0
    assert b"[INFO] [launch.user]: fast mode" not in run.stdout
    assert b"[INFO] [launch.user]: not slow" not in run.stdout
    assert b"[INFO] [launch.user]: shutdown: worker done" in run.stdout
