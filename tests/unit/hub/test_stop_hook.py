"""The hub's stop hook runs the course's own `course_lib stop`, bounded in time and output.

An attack test: a learner who plants a `course_lib` folder in their home must not have the hub
run it after their server stops (it ran as the learner, but on the hub's behalf and with the
hub waiting for it).
"""

from __future__ import annotations

import asyncio
import subprocess
import sys
from pathlib import Path

from course_lib.core.paths import venv_bin_dir
from course_lib.hub.spawner import OUTPUT_LIMIT, leftover_stop_argv, run_bounded

PLANTED = "import pathlib, sys; pathlib.Path(sys.argv[0]).with_name('RAN').write_text('x')\n"


def _plant(home: Path) -> Path:
    package = home / "course_lib"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "__main__.py").write_text(PLANTED)
    return package / "RAN"


def test_a_course_lib_planted_in_the_learners_home_never_runs(tmp_path: Path) -> None:
    ran = _plant(tmp_path)
    python = str(venv_bin_dir() / "python")
    argv = [*leftover_stop_argv(python)[:-1], "--help"]  # the hook's interpreter and module
    env = {"HOME": str(tmp_path), "PATH": "/usr/bin:/bin", "PYTHONPATH": str(tmp_path)}
    text = asyncio.run(run_bounded(argv, env=env, timeout=60))
    assert text is not None and "stop" in text, text  # the course's own command answered
    assert not ran.exists(), "the learner's planted course_lib ran"
    # the hook's old way (its home as the working folder, not isolated) ran the planted one
    subprocess.run([python, "-m", "course_lib", "--help"], cwd=tmp_path, env=env, check=False)
    assert ran.exists(), "the attack itself no longer works: this test proves nothing"


def test_the_hook_keeps_only_the_start_of_a_flood_of_output() -> None:
    flood = [sys.executable, "-c", "import sys; sys.stdout.write('x' * 2_000_000)"]
    text = asyncio.run(run_bounded(flood, env={}, timeout=60))
    assert text is not None and len(text) == OUTPUT_LIMIT


def test_a_hook_that_hangs_is_killed_and_reported() -> None:
    hang = [sys.executable, "-c", "import time; time.sleep(60)"]
    assert asyncio.run(run_bounded(hang, env={}, timeout=0.5)) is None
