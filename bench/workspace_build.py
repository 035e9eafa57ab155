"""Building tf2_msgs as `make setup` does: from a clean copy, then again (nothing to rebuild)."""

from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from course_lib.core.paths import REPO_ROOT, ROSJECT_DIR

GOAL_S = 30.0


def build(workspace: Path) -> float:
    """Return the wall seconds of `python -m course_lib build --workspace <workspace>`."""
    started = time.monotonic()
    done = subprocess.run(
        [sys.executable, "-m", "course_lib", "build", "--workspace", str(workspace)],
        cwd=REPO_ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode != 0:
        sys.exit(f"build failed:\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}")
    return time.monotonic() - started


def main() -> None:
    with tempfile.TemporaryDirectory() as scratch:
        workspace = Path(scratch) / "rosject"
        shutil.copytree(ROSJECT_DIR / "tf2_msgs", workspace / "tf2_msgs")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        first = build(workspace)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        second = build(workspace)
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    load = os.getloadavg()[0]
    print(
        f"tf2_msgs from a clean copy: {first:5.1f} s (goal < {GOAL_S:g} s on 2 cores; "
        f"{cpu:.0f} CPU seconds); "
        f"again, nothing to rebuild: {second:4.1f} s; load average {load:.1f} "
        f"on {os.cpu_count()} cores"
    )


if __name__ == "__main__":
    main()
