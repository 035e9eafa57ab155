"""The world's scheduling (course_lib.core.host.scheduling): batch work at a low weight, its
own session's autogroup too, and never the autogroup of a session it does not lead."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from course_lib.core.host.scheduling import BACKGROUND_NICE

pytestmark = pytest.mark.skipif(sys.platform != "linux", reason="Linux scheduling")

AUTOGROUP = Path("/proc/self/autogroup")
REPORT = (
    "import os; from pathlib import Path; "
    "from course_lib.core.host.scheduling import as_background_work; "
    "print(as_background_work(), os.getpriority(os.PRIO_PROCESS, 0), "
    "Path('/proc/self/autogroup').read_text().split()[-1])"
)


def _run(*, own_session: bool) -> list[str]:
    done = subprocess.run(
        [sys.executable, "-c", REPORT],
        capture_output=True,
        text=True,
        check=True,
        start_new_session=own_session,
    )
    return done.stdout.split()


@pytest.mark.skipif(not AUTOGROUP.exists(), reason="no autogroups on this kernel")
def test_a_session_leader_lowers_its_own_autogroup() -> None:
    assert _run(own_session=True) == ["True", str(BACKGROUND_NICE), str(BACKGROUND_NICE)]


@pytest.mark.skipif(not AUTOGROUP.exists(), reason="no autogroups on this kernel")
def test_a_process_in_anothers_session_leaves_that_sessions_autogroup_alone() -> None:
    # Its autogroup is its session's: the test's own, with the learner's kernel in a lab.
    before = AUTOGROUP.read_text().split()[-1]
    assert _run(own_session=False) == ["True", str(BACKGROUND_NICE), before]
    assert AUTOGROUP.read_text().split()[-1] == before
