"""`make stop` stops the course's processes and nothing else, inside a lab and outside.

The scenario (stop_scenario.py) runs a real `make lab`-style JupyterLab with a terminal opened
through Jupyter's REST and websocket API, in a PID namespace of its own: `make stop` there
cannot reach the other processes of this machine.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
from pid_namespace import namespace_prefix
from suite_env import independent_env

pytestmark = [pytest.mark.ros, pytest.mark.slow]

SCENARIO = Path(__file__).with_name("stop_scenario.py")


@pytest.fixture(scope="module")
def facts() -> dict:
    prefix = namespace_prefix("isolates `make stop` from this host")
    tmp = tempfile.mkdtemp(prefix="ms")
    try:
        done = subprocess.run(
            [*prefix, sys.executable, str(SCENARIO)],
            env=independent_env(TMPDIR=tmp),
            capture_output=True,
            text=True,
            timeout=240,
            check=False,
        )
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    lines = [line for line in done.stdout.splitlines() if line.startswith("{")]
    assert done.returncode == 0 and lines, f"scenario failed:\n{done.stdout}\n{done.stderr}"
    result = json.loads(lines[-1])
    print(f"make stop in a lab terminal ({result['inside_seconds']} s):")
    print(result["inside_output"])
    print(f"make stop outside ({result['outside_seconds']} s):\n{result['outside_output']}")
    return result


def test_in_a_lab_terminal_stop_keeps_the_lab_and_the_learners_programs(facts: dict) -> None:
    alive = facts["alive_after_inside"]
    assert alive == {
        "lab": True,
        "jupyterlab": True,
        "daemon": False,
        "shell": True,
        "editor": True,
        "node": False,
        "stubborn": False,
        "script": True,
        "logger": True,
    }, facts["inside_output"]
    assert facts["shell_answers"]
    assert facts["inside_exit"] == 0


def test_stop_says_what_it_stopped_and_that_the_lab_stays(facts: dict) -> None:
    said, pids = facts["inside_output"], facts["pids"]
    # Ctrl-C first, as a learner would stop it. Its end is said as it came: after SIGTERM only
    # if its rclpy teardown outlasted the grace time (once in a suite run on 2 busy cores)
    assert facts["signals_to_node"][:1] == ["SIGINT"], facts["signals_to_node"]
    node = f"  param_vel (pid {pids['node']})"
    assert f"{node}\n" in said or f"{node} after SIGTERM\n" in said
    assert f"  stubborn (pid {pids['stubborn']}) after SIGKILL\n" in said  # SIGINT, SIGTERM
    assert "  ros2-daemon-" in said and f"(pid {pids['daemon']})" in said
    assert f"This terminal belongs to the lab (pid {pids['lab']})" in said
    # "(pid 22)", not "pid 22": in the test's own PID namespace the shell's 22 begins 227
    assert f"(pid {pids['shell']})" not in said and f"(pid {pids['editor']})" not in said


def test_outside_a_lab_stop_ends_the_lab_and_leaves_only_the_learners_own_program(
    facts: dict,
) -> None:
    """The lab, its nodes and the learner's ROS script stop; a program the learner started
    from a lab terminal to outlive it (it inherited the lab's marker) runs on, and is named."""
    alive = dict(facts["alive_after_outside"])  # the module's facts stay whole for a rerun
    assert alive.pop("logger"), f"make stop killed the learner's own program: {facts}"
    assert not any(alive.values()), alive
    assert facts["left_running"] == ""
    said = facts["outside_output"]
    assert f"  lab (pid {facts['pids']['lab']})" in said, said
    assert "Left running 1 program(s) of yours" in said, said
    assert f"sleep 700 (pid {facts['pids']['logger']})" in said, said
    assert facts["outside_exit"] == 0
