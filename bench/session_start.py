"""Session start-up figures: first parameter list, a late node's first answer, `make lab` again."""

from __future__ import annotations

import os
import signal
import statistics
import subprocess
import sys
import time

from course_lib.core.paths import REPO_ROOT

RUNS = 7

FIRST_LIST = """
import time
t0 = time.monotonic()
from course_lib.session.session import Session
from rclpy.parameter_client import AsyncParameterClient
s = Session()
s.run("parameter_tests", "param_vel")
c = AsyncParameterClient(s.node, "/param_vel_node")
while not c.services_are_ready():
    time.sleep(0.002)
names = s.wait_future(c.list_parameters([], 0), 5.0).result.names
assert "velocity" in names
print(time.monotonic() - t0)
s.close()
"""

LATE_NODE = """
import time
from course_lib.session.session import Session
from rclpy.parameter_client import AsyncParameterClient
s = Session()
time.sleep(1.0)  # a session that has been running for a while
for _ in range({runs}):
    t0 = time.monotonic()
    node = s.run("parameter_tests", "param_vel")
    c = AsyncParameterClient(s.node, "/param_vel_node")
    while True:
        try:
            s.wait_future(c.get_parameters(["velocity"]), 0.05)
            break
        except TimeoutError:
            pass
    print(time.monotonic() - t0, flush=True)
    node.stop()
s.close()
"""


def _python(code: str) -> list[float]:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return [float(line) for line in out.stdout.split()]


def _row(label: str, values: list[float], goal: str) -> None:
    print(
        f"{label:<48} median {statistics.median(values):6.3f} s  "
        f"max {max(values):6.3f} s  (n={len(values)}, goal {goal})"
    )


def main() -> None:
    first = [v for _ in range(RUNS) for v in _python(FIRST_LIST)]
    _row("session start -> first `param list` answer", first, "< 1.5 s")
    _row(
        "node spawned in running session -> 1st answer",
        _python(LATE_NODE.format(runs=RUNS)),
        "< 1 s",
    )
    _row(
        "second `make lab`: until JupyterLab answers", [_lab_start() for _ in range(3)], "seconds"
    )


def _lab_start() -> float:
    """Time `make lab` (already set up) until JupyterLab serves its page, then stop it."""
    t0 = time.monotonic()
    lab = subprocess.Popen(
        ["make", "-s", "lab", "EXTRA=--no-browser --ServerApp.port=0"],
        cwd=REPO_ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    try:
        for line in lab.stdout:
            if "http://127.0.0.1:" in line:
                return time.monotonic() - t0
        raise RuntimeError("JupyterLab never printed its address")
    finally:
        os.killpg(lab.pid, signal.SIGTERM)
        lab.communicate(timeout=20)


if __name__ == "__main__":
    main()
