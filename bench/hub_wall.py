"""What the domain wall costs: a real class hub started with and without it (needs root).

Run: sudo .venv/bin/python -m bench.hub_wall [--learners N] [--environment DIR]
Prints, for each of the two hubs: the hub's start-up (`python -m course_lib hub` to "The
class hub is up", the learners' environment already built), the wall's own check at start,
each learner's server start (sign-in to their server answering through the hub, learners one
after another) and each learner's memory once the server is up and idle (RSS and PSS summed
over their processes; the namespaces' own kernel memory is not in either). Creates test
accounts r2pb-<n> and r2pb-admin and removes them after. Skips (exit 0) when not root.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import psutil

from bench._hub import (
    ADMIN,
    account_pids,
    default_environment,
    remove_account,
    running_hub,
    sign_in,
)
from course_lib.hub.guard.wall import wall_problem


def _memory_mib(name: str) -> tuple[float, float]:
    rss = pss = 0
    for process in account_pids(name):
        with contextlib.suppress(psutil.Error):
            full = process.memory_full_info()
            rss, pss = rss + full.rss, pss + full.pss
    return rss / 2**20, pss / 2**20


def _one_hub(learners: list[str], environment: Path, folder: Path, wall: bool) -> dict:
    with running_hub(learners, environment, folder, wall=wall) as hub:
        starts, memory = [], []
        for name in learners:
            starts.append(sign_in(hub.url, name, hub.passwords[name]))
            time.sleep(3.0)  # the lab settles: its machine service is up
            memory.append(_memory_mib(name))
        return {"up": hub.up_s, "walled": hub.walled, "starts": starts, "memory": memory}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--learners", type=int, default=2)
    parser.add_argument("--environment", type=Path, default=default_environment())
    args = parser.parse_args()
    if os.geteuid() != 0:
        print("hub_wall: skipped (a class hub needs root and creates accounts)")
        return 0
    t0 = time.perf_counter()
    problem = wall_problem()
    print(f"wall check at the hub's start: {(time.perf_counter() - t0) * 1000:.1f} ms "
          f"({'available' if problem is None else problem})")  # fmt: skip
    learners = [f"r2pb-{i}" for i in range(1, args.learners + 1)]
    with tempfile.TemporaryDirectory(prefix="bench-hub-wall-") as tmp:
        Path(tmp).chmod(0o711)  # the progress service's own account enters its state folder
        try:
            for wall in (False, True):  # each hub creates its accounts afresh
                result = _one_hub(learners, args.environment, Path(tmp), wall)
                label = "with the wall   " if result["walled"] else "without the wall"
                starts = result["starts"]
                rss = statistics.mean(m[0] for m in result["memory"])
                pss = statistics.mean(m[1] for m in result["memory"])
                print(
                    f"{label}: hub up in {result['up']:.1f} s; server start per learner "
                    f"{', '.join(f'{s:.1f}' for s in starts)} s (median "
                    f"{statistics.median(starts):.1f} s); idle learner {rss:.0f} MiB RSS, "
                    f"{pss:.0f} MiB PSS",
                    flush=True,
                )
        finally:
            for name in (*learners, ADMIN):
                remove_account(name)
    return 0


if __name__ == "__main__":
    sys.exit(main())
