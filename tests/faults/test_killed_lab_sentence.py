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
from suite_env import independent_env

from course_lib.core.paths import REPO_ROOT
from course_lib.processes.orphans import OWNER_ENV, SPAWNED_ENV, command_tag

pytestmark = pytest.mark.slow

CLEAN_UP = """
import os
from course_lib.core.paths import REPO_ROOT, runtime_dir
from course_lib.lab.leftovers import clean_up_killed_labs
assert str(runtime_dir()).startswith(os.environ["TMPDIR"]), runtime_dir()  # the test's own
(runtime_dir() / "lab-{lab}.clone").write_text(str(REPO_ROOT))
print(clean_up_killed_labs())
"""


def _dead_pid() -> int:
    ended = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"],
        capture_output=True,
        text=True,
        check=True,
    )
    return int(ended.stdout)


@pytest.fixture
def short_tmp() -> Iterator[str]:
    """Yield a TMPDIR of the test's own, short enough to hold the course's runtime folder (a
    longer one, such as pytest's tmp_path, falls back to the user's shared folder in /tmp)."""
    folder = tempfile.mkdtemp(prefix="ks")
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


def test_another_owners_leftover_is_reaped_but_not_counted_as_the_labs(short_tmp: str) -> None:
    lab, other_owner = _dead_pid(), _dead_pid()
    argv = [sys.executable, "-c", "import time; print('up', flush=True); time.sleep(600)"]
    other = subprocess.Popen(
        argv,
        env={**os.environ, OWNER_ENV: f"{other_owner}:1", SPAWNED_ENV: command_tag(argv)},
        start_new_session=True,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert other.stdout is not None and other.stdout.readline() == "up\n"
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
    finally:
        if other.poll() is None:
            other.kill()
            other.wait()
        if other.stdout is not None:
            other.stdout.close()
