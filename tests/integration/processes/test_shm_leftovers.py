"""A killed ROS process's shared-memory segment is removed; a live one's is kept.

In a /dev/shm of the test's own (root and `unshare`, as in the CI): two real rclpy
participants start, one is killed with SIGKILL and leaves its Fast DDS segment behind; the
sweep that `make stop` and every lab's start run removes that one and keeps the other.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.processes.domain import lease_domain
from course_lib.session.session import session_env

pytestmark = [pytest.mark.ros]

REPO = Path(__file__).resolve().parents[3]
# a node that talks on /chatter and hears it: Fast DDS makes a participant's segment when it
# first writes to a reader on this host
NODE = """
import sys, time, rclpy
from std_msgs.msg import String
rclpy.init()
node = rclpy.create_node(sys.argv[1])
heard = []
node.create_subscription(String, "/chatter", heard.append, 10)
talk = node.create_publisher(String, "/chatter", 10)
node.create_timer(0.05, lambda: talk.publish(String(data=sys.argv[1])))
while len({m.data for m in heard}) < int(sys.argv[2]):
    rclpy.spin_once(node, timeout_sec=0.1)
print("up", flush=True)
rclpy.spin(node)
"""
SCENARIO = """
import json, re, signal, subprocess, sys
from pathlib import Path
from course_lib.processes.shm_segments import sweep_stale_segments

NODE = sys.argv[1]  # the test's NODE

def segments():
    names = (p.name for p in Path("/dev/shm").iterdir())
    return {n for n in names if re.fullmatch("fastrtps_[0-9a-f]{16}", n)}

def node(name, talkers):
    argv = [sys.executable, "-c", NODE, name, str(talkers)]
    child = subprocess.Popen(argv, stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "up\\n"
    return child

live = node("live_node", 1)
killed = node("killed_node", 2)  # it hears both: each has written to the other's reader
both = segments()
killed.send_signal(signal.SIGKILL)
killed.wait()
left = segments()
first = sweep_stale_segments(min_age_s=0.0)
kept = segments()
live.send_signal(signal.SIGKILL)
live.wait()
second = sweep_stale_segments(min_age_s=0.0)
print(json.dumps({"both": sorted(both), "left": sorted(left), "first": first.segments,
                  "kept": sorted(kept), "second": second.segments, "end": sorted(segments())}))
"""


@pytest.fixture(scope="module")
def env() -> Iterator[dict[str, str]]:
    lease = lease_domain({})
    try:
        yield {**session_env(lease.domain_id), "PYTHONPATH": str(REPO)}
    finally:
        lease.release()


def test_a_killed_nodes_segment_is_swept_and_a_live_nodes_kept(env: dict[str, str]) -> None:
    unshare = shutil.which("unshare")
    if unshare is None or os.geteuid() != 0:
        pytest.skip("needs root and `unshare` for a /dev/shm of its own (the CI runs as root)")
    script = f'mount -t tmpfs tmpfs /dev/shm && exec {sys.executable} -c "$0" "$@"'
    done = subprocess.run(
        [unshare, "--mount", "sh", "-c", script, SCENARIO, NODE],
        env=env, capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.splitlines()[-1])
    assert len(seen["both"]) == 2, seen  # a segment for each node
    assert seen["left"] == seen["both"], "SIGKILL left no segment: nothing to test"
    assert seen["first"] == 1 and len(seen["kept"]) == 1, seen  # the killed node's went
    assert seen["second"] == 1 and seen["end"] == [], seen  # the one kept was the live node's
