"""`make test`: the whole suite (unit, integration, notebooks, browser) in one pytest run."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

from ..core.paths import NOTEBOOKS_DIR, REPO_ROOT
from ..ros2.node.direct import TEARDOWN_DUMPS_ENV
from .testing import TEST_ENV

__all__ = ["pytest_argv", "run_tests"]


def pytest_argv(extra: list[str]) -> list[str]:
    """Return the pytest command line: tests/ and every notebook, one worker per core and two
    more: the tests wait on real processes much of the time (on 2 cores, 2 workers left them
    65% idle and took 714-730 s; on fresh clones 3 took 586-603 s, 4 took 507-578 s with the
    cores 84-89% busy and no rerun in 24 of 25 runs. A fifth worker took 487-531 s at 93-95%
    busy, but at that load tests failed that never fail at 4: a lesson's Run All lost to a
    kernel websocket closed as it opened, a panel that missed a value for 10 s)."""
    cores = os.cpu_count() or 1
    workers = str(cores + 2) if cores >= 2 else "0"
    notebooks = ["notebooks"] if any(NOTEBOOKS_DIR.glob("*.ipynb")) else []
    return [
        sys.executable,
        "-m",
        "pytest",
        "tests",
        *notebooks,
        "--nbval-lax",
        "--nbval-sanitize-with",
        "tests/nbval_sanitize.cfg",
        "-n",
        workers,
        "--dist",
        "loadfile",
        # tests/conftest.py deals the longest files first; xdist's own order (by test count)
        # dealt the long one-test files last, one worker busy alone for 90 s at the end
        "--no-loadscope-reorder",
        # Tests of real processes on 2 busy cores: one that fails is run again (up to twice)
        # and reported as a rerun, so an intermittent failure stays visible in the summary.
        "--reruns",
        "2",
        "--reruns-delay",
        "1",
        *extra,
    ]


def run_tests(extra: list[str]) -> int:
    """Run the suite with the test environment; return pytest's exit code.

    A `ros2` command whose teardown is cut short leaves its threads' tracebacks in
    test-artifacts/teardown/ (tests/conftest.py names them at the end of the run).
    """
    dumps = REPO_ROOT / "test-artifacts" / "teardown"
    shutil.rmtree(dumps, ignore_errors=True)
    dumps.mkdir(parents=True)
    env = {**os.environ, **TEST_ENV, TEARDOWN_DUMPS_ENV: str(dumps)}
    code = subprocess.run(pytest_argv(extra), cwd=REPO_ROOT, env=env, check=False).returncode
    if code == 5:
        print("pytest collected no tests: the suite is missing.", file=sys.stderr)
    return code
