"""How fast this host runs Python, printed under the suite's CPU table.

The same commit ran the suite in 520-530 s on one host and 1144 s on another of the same kind
(2 cores): a suite's time says little without the host's speed beside it. Two figures, each
from fresh interpreters: the CPU a fixed loop takes, and how long a bare interpreter takes to
start (the `ros2` commands, kernels and nodes the suite starts pay it each time).
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time

__all__ = ["LOOP_ADDITIONS", "host_speed_line", "loop_cpu_s", "start_ms"]

LOOP_ADDITIONS = 5_000_000

_LOOP = """\
import time
started = time.process_time()
s = 0
for i in range({count}):
    s += i
print(time.process_time() - started)
"""


def loop_cpu_s(count: int = LOOP_ADDITIONS) -> float:
    """Return the CPU seconds a fresh interpreter spends on `count` additions (its start aside)."""
    done = subprocess.run(
        [sys.executable, "-S", "-c", _LOOP.format(count=count)],
        capture_output=True,
        text=True,
        check=True,
    )
    return float(done.stdout)


def start_ms(times: int = 5) -> float:
    """Return the median wall milliseconds of a bare interpreter start (`python -S -c pass`)."""
    walls = []
    for _ in range(times):
        started = time.perf_counter()
        subprocess.run([sys.executable, "-S", "-c", "pass"], check=True)
        walls.append((time.perf_counter() - started) * 1000)
    return statistics.median(walls)


def host_speed_line(count: int = LOOP_ADDITIONS) -> str:
    """Return one line with both figures, for the end of a suite run."""
    return (
        f"host speed: {count / 1e6:g}M additions in {loop_cpu_s(count):.2f} CPU-s; "
        f"a bare interpreter starts in {start_ms():.0f} ms (median of 5)"
    )
