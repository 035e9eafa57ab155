"""The next lab's sentence about a killed lab counts that lab's leftovers, not another's.

A lab reaps every leftover of its user as it starts (another session's, a test's), but the
sentence it prints is about the killed lab: in a CI run, a process another test left was
counted ("the 1 process(es) left running are stopped" for a lab nothing of which ran).
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import tempfile
from collections.abc import Iterator

import pytest
from leftovers import dead_pid, judge_leftover
from suite_env import independent_env

from course_lib.core.paths import REPO_ROOT
from course_lib.processes.orphans import OWNER_ENV, SPAWNED_ENV, command_tag

pytestmark = pytest.mark.slow

SLEEP = [sys.executable, "-c", "import time; print('up', flush=True); time.sleep(600)"]
CLEAN_UP = """
import os
from course_lib.core.paths import REPO_ROOT, runtime_dir
from course_lib.lab.leftovers import clean_up_killed_labs
assert str(runtime_dir()).startswith(os.environ["TMPDIR"]), runtime_dir()  # the test's own
(runtime_dir() / "lab-{lab}.clone").write_text(str(REPO_ROOT))
print(clean_up_killed_labs())
"""


@pytest.fixture
def short_tmp() -> Iterator[str]:
    """Yield a TMPDIR of the test's own, short enough to hold the course's runtime folder (a
    longer one, such as pytest's tmp_path, falls back to the user's shared folder in /tmp)."""
    folder = tempfile.mkdtemp(prefix="ks")
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


def test_another_owners_leftover_is_reaped_but_not_counted_as_the_labs(short_tmp: str) -> None:
    env = {**os.environ, OWNER_ENV: f"{dead_pid()}:1", SPAWNED_ENV: command_tag(SLEEP)}
    started: list[subprocess.Popen[str]] = []

    def start() -> subprocess.Popen[str]:
        leftover = subprocess.Popen(SLEEP, env=env, stdout=subprocess.PIPE, text=True)
        started.append(leftover)
        return leftover

    def judge(other: subprocess.Popen[str]) -> bool:
        lab = dead_pid()
        said = subprocess.run(
            [sys.executable, "-c", CLEAN_UP.format(lab=lab)],
            env=independent_env(TMPDIR=short_tmp),
            cwd=REPO_ROOT,
            capture_output=True,
            text=True,
            timeout=60,
            check=True,
        ).stdout.strip()
        assert said == (
            f"The previous lab (pid {lab}) ended without stopping cleanly (killed or crashed): "
            "nothing of it was running any more, and its files are removed."
        ), said
        # reaped all the same (by this clean-up, or by another session of this user first)
        assert other.wait(timeout=5) == -signal.SIGKILL
        return True

    try:
        assert judge_leftover(start, judge)  # restarted if another session reaps it first
    finally:
        for proc in started:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
            if proc.stdout is not None:
                proc.stdout.close()
