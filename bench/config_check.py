"""`make check-config`'s wall time: an instructor runs it after every edit of config/."""

from __future__ import annotations

import statistics
import subprocess
import sys
import time

from course_lib.core.paths import REPO_ROOT

RUNS = 5
GOAL_S = 1.0


def main() -> None:
    times = []
    for _ in range(RUNS):
        started = time.monotonic()
        subprocess.run(
            [sys.executable, "-m", "course_lib", "check-config"],
            cwd=REPO_ROOT, check=True, capture_output=True,
        )  # fmt: skip
        times.append(time.monotonic() - started)
    median = statistics.median(times)
    verdict = "meets" if median < GOAL_S else "misses"
    print(
        f"check-config: median {median:.2f} s, max {max(times):.2f} s over {RUNS} runs "
        f"({verdict} the goal of < {GOAL_S:g} s)"
    )


if __name__ == "__main__":
    main()
