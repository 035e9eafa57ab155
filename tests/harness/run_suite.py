"""`make test`: the whole suite (unit, integration, notebooks, browser) in one pytest run.

`python tests/harness/run_suite.py [pytest options]`; the test harness lives beside the tests,
not in the course's package.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

from suite_env import TEST_ENV

from course_lib.core.paths import NOTEBOOKS_DIR, REPO_ROOT
from course_lib.ros2.node.direct import TEARDOWN_DUMPS_ENV

__all__ = ["pytest_argv", "run_tests"]


def pytest_argv(extra: list[str]) -> list[str]:
    """Return the pytest command line: tests/ and every notebook, one worker per core and two
    more. The tests wait on real processes much of the time, so one worker per core leaves the
    cores idle between waits; two more keep them busy, and more than that overloads them until
    tests of real processes miss their timeouts (a kernel's websocket, a panel's value)."""
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
        # would deal the long one-test files last, leaving one worker busy alone at the end
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


if __name__ == "__main__":
    sys.exit(run_tests(sys.argv[1:]))
