"""Wall time of the full nbval run: every lesson notebook executed as `make test` does.

Run: .venv/bin/python -m bench.nbval_wall   (BENCH_NBVAL=0 skips it; it takes minutes)
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time

from run_suite import pytest_argv
from suite_env import TEST_ENV

from course_lib.core.paths import NOTEBOOKS_DIR, REPO_ROOT


def main() -> None:
    notebooks = sorted(NOTEBOOKS_DIR.glob("*.ipynb"))
    if os.environ.get("BENCH_NBVAL") == "0":
        print("nbval wall time: skipped (BENCH_NBVAL=0)")
        return
    if not notebooks:
        print("nbval wall time: no notebooks in notebooks/ yet")
        return
    argv = [a for a in pytest_argv(["-q", "-p", "no:cacheprovider"]) if a != "tests"]
    env = {**os.environ, **TEST_ENV}
    start = time.monotonic()
    proc = subprocess.run(argv, cwd=REPO_ROOT, env=env, capture_output=True, text=True)
    wall = time.monotonic() - start
    summary = next(
        (ln for ln in reversed(proc.stdout.splitlines()) if re.search(r"passed|failed", ln)), ""
    )
    workers = argv[argv.index("-n") + 1]
    print(
        f"{'nbval, all ' + str(len(notebooks)) + ' notebooks (-n ' + workers + ')':<48} "
        f"{wall:7.1f} s   ({summary.strip('= ') or 'exit ' + str(proc.returncode)})"
    )
    if proc.returncode not in (0, 5):
        print(proc.stdout[-2000:], file=sys.stderr)


if __name__ == "__main__":
    main()
