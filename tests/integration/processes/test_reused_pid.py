"""A child's pid, once the child is gone, may name another process: stopping never hits it.

Everything `spawn` starts leads a process group of its own, so a `killpg` on the pid of a
child that ended long ago would kill whatever process got that pid since (on a machine whose
pids wrap every few minutes: another lab's JupyterLab, another kernel's node). Kernels stop
every child they ever started when they close. The scenario runs in a PID namespace of its own,
where the next pid can be chosen (/proc/sys/kernel/ns_last_pid): a "stranger" gets the child's
old pid and leads its own group, as another session's process would.
"""

from __future__ import annotations

import json
import subprocess
import sys

from pid_namespace import namespace_prefix
from suite_env import independent_env

SCENARIO = """
import json, subprocess, time
from course_lib.processes.children import spawn

def stranger_with_pid(pid):
    # A start time counts clock ticks (10 ms): a real reuse of a pid comes a whole wrap of the
    # pid space later, never within the tick the child started in, so neither may this one.
    time.sleep(0.05)
    with open("/proc/sys/kernel/ns_last_pid", "w") as f:
        f.write(str(pid - 1))
    stranger = subprocess.Popen(["sleep", "60"], start_new_session=True)
    assert stranger.pid == pid, (stranger.pid, pid)
    return stranger

def survives(stranger):
    time.sleep(0.3)
    alive = stranger.poll() is None
    stranger.kill()
    stranger.wait()
    return alive

facts = {}
child = spawn(["true"], name="node")
child.stop()
stranger = stranger_with_pid(child.pid)
child.stop()  # again, as a closing session stops every child it ever started
facts["survives_a_second_stop"] = survives(stranger)

child = spawn(["true"], name="node")
child.wait()  # it ended by itself and was reaped; stop() comes later
stranger = stranger_with_pid(child.pid)
child.stop()
facts["survives_a_late_first_stop"] = survives(stranger)

child = spawn(["sh", "-c", "sleep 60 & echo $!"], name="node")  # leaves a grandchild
grandchild = int(child.wait_for_line(r"^\\d+$", 10).text)
child.stop()
time.sleep(0.3)
try:
    with open(f"/proc/{grandchild}/stat") as f:
        facts["grandchild_left"] = f.read().rsplit(")", 1)[1].split()[0] != "Z"
except OSError:
    facts["grandchild_left"] = False
print(json.dumps(facts))
"""


def test_stopping_a_gone_child_never_kills_the_process_that_got_its_pid() -> None:
    done = subprocess.run(
        [*namespace_prefix("gives the scenario its own pids"), sys.executable, "-c", SCENARIO],
        env=independent_env(),
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    facts = json.loads(done.stdout.splitlines()[-1])
    assert facts == {
        "survives_a_second_stop": True,
        "survives_a_late_first_stop": True,
        "grandchild_left": False,  # what the child left in its group still goes with it
    }, done.stderr
