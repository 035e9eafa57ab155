"""`ros2 daemon start|stop|status`, the command's own hidden node, --no-daemon, -s, --spin-time."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.processes.domain import lease_domain
from course_lib.ros2.api import nodes_and_params as api
from course_lib.ros2.node.connect import daemon_pids, daemon_running
from course_lib.session.session import session_env

pytestmark = pytest.mark.ros

REPO = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def env() -> Iterator[dict[str, str]]:
    """Yield a terminal's environment in a leased domain (no daemon left afterwards)."""
    lease = lease_domain({})
    env = {**session_env(lease.domain_id), "PYTHONPATH": str(REPO), "COLUMNS": "80"}
    yield env
    _ros2(env, "daemon stop")
    lease.release()


def _popen(env: dict[str, str], command: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-m", "course_lib.ros2.command.cli", *shlex.split(command)],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def _ros2(env: dict[str, str], command: str) -> tuple[str, str, int]:
    proc = _popen(env, command)
    out, err = proc.communicate(timeout=60)
    return out, err, proc.returncode


def test_daemon_verbs_print_what_ros2cli_prints(env: dict[str, str]) -> None:
    domain = env["ROS_DOMAIN_ID"]
    _ros2(env, "daemon stop")
    assert _ros2(env, "daemon status") == ("The daemon is not running\n", "", 0)
    assert _ros2(env, "daemon stop") == ("The daemon is not running\n", "", 0)
    assert _ros2(env, "daemon start") == ("The daemon has been started\n", "", 0)
    assert len(daemon_pids(domain)) == 1
    assert _ros2(env, "daemon status") == ("The daemon is running\n", "", 0)
    assert _ros2(env, "daemon start") == ("The daemon is already running\n", "", 0)
    assert _ros2(env, "daemon stop") == ("The daemon has been stopped\n", "", 0)
    assert not daemon_pids(domain)  # gone when `stop` returns, as ros2cli waits for it
    assert _ros2(env, "daemon status") == ("The daemon is not running\n", "", 0)


def test_daemon_help_and_refused_debug(env: dict[str, str]) -> None:
    out, _err, code = _ros2(env, "daemon")
    assert code == 0 and "Commands:\n  start   Start the daemon if it isn't running\n" in out
    assert "  status  Output the status of the daemon\n" in out
    assert "  stop    Stop the daemon if it is running\n" in out
    out, err, code = _ros2(env, "daemon start --debug")
    assert (out, code) == ("", 1) and "--debug` is not part of this course" in err
    assert not daemon_running(env["ROS_DOMAIN_ID"])


def test_no_daemon_lists_its_own_node_and_starts_no_daemon(env: dict[str, str]) -> None:
    _ros2(env, "daemon stop")
    proc = _popen(env, "node list --all --no-daemon")
    out, err, code = (*proc.communicate(timeout=60), proc.returncode)
    assert (err, code) == ("", 0)
    assert f"/_ros2cli_{proc.pid}\n" in out
    assert not daemon_running(env["ROS_DOMAIN_ID"]) and not daemon_pids(env["ROS_DOMAIN_ID"])


def test_daemon_node_is_named_as_ros2clis(env: dict[str, str]) -> None:
    out, _err, code = _ros2(env, "node list -a")
    assert code == 0
    assert re.search(rf"^/_ros2cli_daemon_{env['ROS_DOMAIN_ID']}_[0-9a-f]{{32}}$", out, re.M), out


def test_the_daemon_offers_no_service_as_ros2clis(env: dict[str, str]) -> None:
    """ros2cli's daemon starts neither parameter nor type description services."""
    assert _ros2(env, "daemon start")[2] == 0
    out, err, code = _ros2(env, "service list --include-hidden-services --no-daemon")
    assert (err, code) == ("", 0)
    assert "_ros2cli_daemon" not in out, out
    out, _err, _code = _ros2(env, "node list -a")
    assert "/_ros2cli_daemon_" in out, out  # the daemon was there to be asked


def test_use_sim_time_runs_on_a_node_of_its_own(env: dict[str, str]) -> None:
    _ros2(env, "daemon stop")
    out, _err, code = _ros2(env, "topic list -s")
    assert code == 0 and "/clock\n" in out  # the command's own node subscribes to /clock
    assert not daemon_pids(env["ROS_DOMAIN_ID"])
    refused = api.ros2("node list --use-sim-time")  # cells share one node on wall time
    assert refused.exit_code == 1 and "--use-sim-time needs a node" in refused.stderr


def test_spin_time_is_waited_for_by_a_fresh_node(env: dict[str, str]) -> None:
    start = time.monotonic()
    _out, _err, code = _ros2(env, "node list --no-daemon --spin-time 2")
    assert code == 0 and time.monotonic() - start >= 2.0
