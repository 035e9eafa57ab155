"""Four course sessions on one host at once: each sees its own node and none of the others'."""

from __future__ import annotations

import re

import pytest
from jupyter_kernels import Kernel

pytestmark = [pytest.mark.ros, pytest.mark.slow]

SESSIONS = 4

START = """
import time
from course_lib.session.session import get_session
from course_lib.notebook.magics import run_line
session = get_session()
node = session.run("parameter_tests", "param_vel", "--ros-args", "-r", "__node:=vel_{i}")
deadline = time.monotonic() + 15
while "/vel_{i}" not in run_line("node list").output.stdout and time.monotonic() < deadline:
    time.sleep(0.05)
print("domain", session.domain_id)
"""


def test_four_sessions_never_see_each_other(start_kernel) -> None:
    kernels: list[Kernel] = [start_kernel() for _ in range(SESSIONS)]
    # the four sessions start at the same time (no threads here: jupyter_client's blocking
    # client leaves an event loop per thread)
    submitted = [kernel.submit(START.format(i=i)) for i, kernel in enumerate(kernels)]
    started = [kernel.collect(msg, 60.0) for kernel, msg in zip(kernels, submitted, strict=True)]
    for out in started:
        assert not out.error, out.everything
    domains = [int(re.search(r"domain (\d+)", out.text)[1]) for out in started]
    assert len(set(domains)) == SESSIONS, f"sessions share a domain: {domains}"
    # every node is up now; each session lists nodes and parameters once more
    for i, kernel in enumerate(kernels):
        nodes = kernel.ok("%load_ext course_lib.notebook.magics\n%ros2 node list").text
        assert f"/vel_{i}\n" in nodes, nodes
        others = [f"/vel_{j}" for j in range(SESSIONS) if j != i and f"/vel_{j}" in nodes]
        assert not others, f"session {i} (domain {domains[i]}) sees {others}"
        params = kernel.ok("%ros2 param list").text
        listed = [line for line in params.splitlines() if line.endswith(":")]
        assert listed == [f"/vel_{i}:"], params
