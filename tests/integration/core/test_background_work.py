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
    """Run REPORT as a session's leader, or as a child of one (`sh`, which then prints its
    session's autogroup nice after REPORT has run); return the words printed."""
    env = {k: v for k, v in os.environ.items() if k != CLASS_HOST_ENV}
    if class_host:
        env[CLASS_HOST_ENV] = "1"
    command = [sys.executable, "-c", REPORT]
    if not own_session:
        # The leader is `sh`, as a kernel leads the session a lab starts a world in; the
        # test's own session may be init's, which has no autogroup to read.
        command = [
            "sh",
            "-c",
            '"$0" -c "$1" && cut -d" " -f3 /proc/self/autogroup',
            sys.executable,
            REPORT,
        ]
    done = subprocess.run(
        command, capture_output=True, text=True, check=True, start_new_session=True, env=env
    )
    return done.stdout.split()


@needs_autogroups
def test_on_a_class_host_a_session_leader_lowers_its_own_autogroup() -> None:
    nice = str(CLASS_NICE)
    assert _run(own_session=True, class_host=True) == ["True", "True", nice, nice]


@needs_autogroups
def test_a_process_in_anothers_session_leaves_that_sessions_autogroup_alone() -> None:
    # the session's autogroup reads nice 0 in the child and in its leader after the child ran
    assert _run(own_session=False, class_host=True) == ["True", "True", str(CLASS_NICE), "0", "0"]


@needs_autogroups
def test_on_a_learners_own_computer_background_work_is_batch_at_its_usual_weight() -> None:
    assert _run(own_session=True, class_host=False) == ["True", "True", "0", "0"]
