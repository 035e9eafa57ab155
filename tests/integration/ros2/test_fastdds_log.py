"""Fast DDS's own log stays out of a command's output.

Participants starting at once on a busy host (a class, the test workers) race for the same
host-wide shared-memory ports (`fastrtps_port7000`, 7001, ...). The one that finds a port's
lock held printed `[RTPS_TRANSPORT_SHM Error] Failed init_port ...` before the command's own
text, then took the next port: the CI saw it twice in golden cases. Here the locks of the
first three ports are held on purpose, in a /dev/shm of the test's own.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator

import pytest
from own_shm import domain_env, run_in_own_shm

pytestmark = [pytest.mark.ros]

HELD_PORTS = range(7000, 7003)
# Holds each port's two locks, then runs the command given to it; prints what it printed.
HOLDER = f"""
import fcntl, json, os, subprocess, sys
held = []
for port in {list(HELD_PORTS)}:
    for lock in ("_el", "_sl"):
        fd = os.open(f"/dev/shm/fastrtps_port{{port}}{{lock}}", os.O_CREAT | os.O_RDWR)
        fcntl.flock(fd, fcntl.LOCK_EX)
        held.append(fd)
done = subprocess.run(sys.argv[1:], capture_output=True, text=True, timeout=60)
print(json.dumps([done.returncode, done.stdout, done.stderr]))
"""


@pytest.fixture(scope="module")
def env() -> Iterator[dict[str, str]]:
    with domain_env() as env:
        yield env


def _in_own_shm(command: list[str], env: dict[str, str]) -> tuple[int, str, str]:
    """Run `command` with a /dev/shm of its own whose first ports' locks are held."""
    code, stdout, stderr = run_in_own_shm(HOLDER, *command, env=env, timeout=90)
    return code, stdout, stderr


def test_a_held_shared_memory_port_prints_nothing(env: dict[str, str]) -> None:
    cli = [sys.executable, "-m", "course_lib.ros2.command.cli"]
    code, stdout, stderr = _in_own_shm([*cli, "node", "list", "--no-daemon"], env)
    assert (code, stdout, stderr) == (0, "", "")


def test_the_profile_still_holds_the_course_discovery_settings() -> None:
    """The log setting wraps the profiles in a <dds> root: the discovery timing is still read."""
    from course_lib.ros2.node.discovery import profile_timing
    from course_lib.session.session import FASTDDS_PROFILE

    assert profile_timing(FASTDDS_PROFILE).floor_s == pytest.approx(1.1)
