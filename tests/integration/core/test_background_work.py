"""The world's scheduling (course_lib.core.host.scheduling): batch work everywhere; on a
class's host at a low weight too, its own session's autogroup as well, and never the
autogroup of a session it does not lead."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from course_lib.core.host.scheduling import CLASS_HOST_ENV, CLASS_NICE

pytestmark = pytest.mark.skipif(sys.platform != "linux", reason="Linux scheduling")

AUTOGROUP = Path("/proc/self/autogroup")
# A thread already running (as a world's ROS and Fast DDS threads are once it is up) is
# reported, not the calling one: every thread the process has is background work.
REPORT = (
    "import os, threading; from pathlib import Path; "
    "from course_lib.core.host.scheduling import as_background_work; "
    "ids = []; up, go = threading.Event(), threading.Event(); "
    "run = lambda: (ids.append(threading.get_native_id()), up.set(), go.wait()); "
    "threading.Thread(target=run).start(); up.wait(); "
    "done = as_background_work(); tid = ids[0]; "
    "print(done, os.sched_getscheduler(tid) == os.SCHED_BATCH, "
    "os.getpriority(os.PRIO_PROCESS, tid), Path('/proc/self/autogroup').read_text().split()[-1]); "
    "go.set()"
)
needs_autogroups = pytest.mark.skipif(not AUTOGROUP.exists(), reason="no autogroups here")


def _run(*, own_session: bool, class_host: bool) -> list[str]:
    env = {k: v for k, v in os.environ.items() if k != CLASS_HOST_ENV}
    if class_host:
        env[CLASS_HOST_ENV] = "1"
    done = subprocess.run(
        [sys.executable, "-c", REPORT],
        capture_output=True,
        text=True,
        check=True,
        start_new_session=own_session,
        env=env,
    )
    return done.stdout.split()


@needs_autogroups
def test_on_a_class_host_a_session_leader_lowers_its_own_autogroup() -> None:
    nice = str(CLASS_NICE)
    assert _run(own_session=True, class_host=True) == ["True", "True", nice, nice]


@needs_autogroups
def test_a_process_in_anothers_session_leaves_that_sessions_autogroup_alone() -> None:
    # Its autogroup is its session's: the test's own, with the learner's kernel in a lab.
    before = AUTOGROUP.read_text().split()[-1]
    assert _run(own_session=False, class_host=True) == ["True", "True", str(CLASS_NICE), before]
    assert AUTOGROUP.read_text().split()[-1] == before


@needs_autogroups
def test_on_a_learners_own_computer_background_work_is_batch_at_its_usual_weight() -> None:
    assert _run(own_session=True, class_host=False) == ["True", "True", "0", "0"]
