"""`python -m course_lib stop` reaches the clone it runs from, and only when asked to stop.

Before: `stop --help` printed no help and stopped every course process of the user at once
(a second clone's hub, its learners' labs and two daemons went with it, in the issue's try),
and any argument was ignored. Now `--help` prints the usage, an unknown argument is refused
with it, and a stop leaves another clone's course processes running and names them;
`--all` stops them too. Run in a PID namespace of its own: nothing of this host is reached.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile

import pytest
from pid_namespace import namespace_prefix
from suite_env import independent_env

pytestmark = [pytest.mark.slow]

OTHER_CLONE = "/srv/another-clone-of-the-course"

# Two owners, each a course process tree of one clone: a spawned `sleep` of each (the other
# clone's as its course tags it), then the four stops, with who is alive after each.
_SCENARIO = r"""
import json, os, subprocess, sys, time
OWNER = '''
import sys, time
from course_lib.processes import children
if sys.argv[1] != "here":
    children.REPO_ROOT = sys.argv[1]
child = children.spawn(["sleep", "300"], name=sys.argv[2])
print(child.pid, flush=True)
time.sleep(300)
'''
owners, pids = [], {}
for clone, name in (("here", "our-node"), (sys.argv[1], "their-node")):
    argv = [sys.executable, "-c", OWNER, clone, name]
    owner = subprocess.Popen(argv, stdout=subprocess.PIPE, text=True)
    pids[name] = int(owner.stdout.readline())
    owners.append(owner)

def running(pid):
    try:
        return open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False

def alive():
    return {name: running(pid) for name, pid in pids.items()}

steps = {}
tries = (("help", ["--help"]), ("bogus", ["--bogus"]), ("stop", []), ("all", ["--all"]))
for label, args in tries:
    argv = [sys.executable, "-m", "course_lib", "stop", *args]
    done = subprocess.run(argv, capture_output=True, text=True)
    time.sleep(0.3)
    steps[label] = {"rc": done.returncode, "out": done.stdout + done.stderr, "alive": alive()}
for owner in owners:
    owner.kill()
print(json.dumps({"pids": pids, "steps": steps}))
"""


@pytest.fixture(scope="module")
def steps() -> dict:
    prefix = namespace_prefix("isolates `python -m course_lib stop` from this host")
    tmp = tempfile.mkdtemp(prefix="sr")
    try:
        done = subprocess.run(
            [*prefix, sys.executable, "-c", _SCENARIO, OTHER_CLONE],
            env=independent_env(TMPDIR=tmp), capture_output=True, text=True, timeout=180,
            check=False,
        )  # fmt: skip
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    lines = [line for line in done.stdout.splitlines() if line.startswith("{")]
    assert done.returncode == 0 and lines, f"scenario failed:\n{done.stdout}\n{done.stderr}"
    return json.loads(lines[-1])["steps"]


def test_help_prints_the_usage_and_stops_nothing(steps: dict) -> None:
    assert steps["help"]["rc"] == 0 and "usage: python -m course_lib stop" in steps["help"]["out"]
    assert "--all" in steps["help"]["out"]
    assert steps["help"]["alive"] == {"our-node": True, "their-node": True}, steps["help"]


def test_an_unknown_argument_is_refused_and_stops_nothing(steps: dict) -> None:
    bogus = steps["bogus"]
    assert bogus["rc"] == 2 and "unrecognized arguments: --bogus" in bogus["out"], bogus
    assert bogus["alive"] == {"our-node": True, "their-node": True}, bogus


def test_a_stop_leaves_another_clones_processes_and_names_them(steps: dict) -> None:
    stop = steps["stop"]
    assert stop["alive"] == {"our-node": False, "their-node": True}, stop["out"]
    assert "  our-node (pid " in stop["out"]
    assert f"of another clone ({OTHER_CLONE})" in stop["out"], stop["out"]
    assert "  their-node (pid " in stop["out"] and "--all" in stop["out"]


def test_all_stops_every_clones_processes(steps: dict) -> None:
    assert steps["all"]["alive"] == {"our-node": False, "their-node": False}, steps["all"]
    assert "  their-node (pid " in steps["all"]["out"]
