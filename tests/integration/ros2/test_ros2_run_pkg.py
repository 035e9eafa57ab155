"""`ros2 run` and `ros2 pkg` through the console command, against the course workspace."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from course_lib.core import ament
from course_lib.core.errors import PackageNotFoundError
from course_lib.processes.domain import lease_domain

REPO = Path(__file__).resolve().parents[3]
pytestmark = pytest.mark.ros


def _has_workspace() -> bool:
    try:
        return "param_vel" in ament.package_executables("parameter_tests", ament.workspace_env())
    except PackageNotFoundError:
        return False


needs_workspace = pytest.mark.skipif(not _has_workspace(), reason="rosject not built")


def _ros2(*args: str, env: dict[str, str] | None = None, **kwargs):  # type: ignore[no-untyped-def]
    env = {**ament.workspace_env(), "PYTHONPATH": str(REPO), **(env or {})}
    env.pop("ROS_DOMAIN_ID", None)
    if "LEASED" in env:
        env["ROS_DOMAIN_ID"] = env.pop("LEASED")
    return subprocess.run(
        [sys.executable, "-m", "course_lib.ros2.command.cli", *args],
        env=env,
        capture_output=True,
        text=True,
        timeout=30,
        check=False,
        **kwargs,
    )


def test_run_missing_package_and_executable() -> None:
    out = _ros2("run", "no_such_pkg", "param_vel")
    assert (out.stdout, out.stderr, out.returncode) == ("", "Package 'no_such_pkg' not found\n", 1)
    if _has_workspace():
        out = _ros2("run", "parameter_tests", "no_such_exec")
        assert (out.stdout, out.stderr, out.returncode) == ("", "No executable found\n", 1)


@needs_workspace
def test_pkg_executables_and_prefix() -> None:
    assert _ros2("pkg", "executables", "parameter_tests").stdout == "parameter_tests param_vel\n"
    prefix = _ros2("pkg", "prefix", "parameter_tests").stdout.strip()
    assert Path(prefix) == ament.package_prefix("parameter_tests", ament.workspace_env())
    assert _ros2("pkg", "prefix", "nope").stderr == "Package not found\n"


@needs_workspace
def test_run_interrupted_by_ctrl_c_prints_interrupt_and_exits_254() -> None:
    # The golden tutorial node (no KeyboardInterrupt handling) runs through --prefix, so the
    # test does not depend on how the workspace's own entry script was built.
    node = REPO / "tests" / "golden" / "ros2" / "nodes" / "param_vel_node.py"
    lease = lease_domain({})  # never a fixed id: parallel sessions would see this node
    env = {
        **ament.workspace_env(),
        "PYTHONPATH": str(REPO),
        "ROS_DOMAIN_ID": str(lease.domain_id),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "PYTHONUNBUFFERED": "1",
    }
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "course_lib.ros2.command.cli",
            "run",
            "--prefix",
            f"{sys.executable} {node}",
            "parameter_tests",
            "param_vel",
            "--ros-args",
            "-p",
            "velocity:=0.1",
        ],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        first = proc.stderr.readline()
        assert "[param_vel_node]: Velocity parameter is: 0.100000" in first
        os.killpg(proc.pid, signal.SIGINT)  # what Ctrl-C in a terminal does
        stdout, _ = proc.communicate(timeout=20)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
        lease.release()
    assert (stdout, proc.returncode) == ("[ros2run]: Interrupt\n", 254)


def _learner_workspace(root: Path) -> Path:
    """Make an install prefix holding a `parameter_tests` of the learner's own."""
    (root / "share/ament_index/resource_index/packages").mkdir(parents=True)
    (root / "share/ament_index/resource_index/packages/parameter_tests").touch()
    launch = root / "share/parameter_tests/launch/test_parameters.launch.py"
    launch.parent.mkdir(parents=True)
    launch.write_text(
        "from launch import LaunchDescription\n"
        "from launch.actions import DeclareLaunchArgument\n\n\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([DeclareLaunchArgument('from_my_workspace')])\n"
    )
    exe = root / "lib/parameter_tests/param_vel"
    exe.parent.mkdir(parents=True)
    exe.write_text("#!/bin/sh\necho my own param_vel\n")
    exe.chmod(0o755)
    return root


@needs_workspace
@pytest.mark.parametrize("mine_first", [True, False])
def test_packages_resolve_in_the_callers_prefix_order(tmp_path: Path, mine_first: bool) -> None:
    mine = _learner_workspace(tmp_path / "my_ws" / "install")
    course = ament.package_prefix("parameter_tests", ament.workspace_env())
    order = [mine, course] if mine_first else [course, mine]
    winner = order[0]
    lease = lease_domain({})  # as a lab's terminal: the course's settings are underlaid
    env = {"AMENT_PREFIX_PATH": os.pathsep.join(map(str, order)), "LEASED": str(lease.domain_id)}
    assert _ros2("pkg", "prefix", "parameter_tests", env=env).stdout == f"{winner}\n"
    executables = _ros2("pkg", "executables", "parameter_tests", "--full-path", env=env)
    assert executables.stdout == f"{winner / 'lib/parameter_tests/param_vel'}\n"
    launch = _ros2("launch", "parameter_tests", "test_parameters.launch.py", "-s", env=env)
    assert ("from_my_workspace" in launch.stdout) is mine_first, launch.stderr
    if mine_first:  # the course's own param_vel is a node: only the learner's one is run
        run = _ros2("run", "parameter_tests", "param_vel", env=env)
        assert (run.stdout, run.returncode) == ("my own param_vel\n", 0)
    lease.release()
