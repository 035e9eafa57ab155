"""A killed ROS process's shared-memory segment is removed; a live one's is kept.

In a /dev/shm of the test's own (root and `unshare`, as in the CI): two real rclpy
participants start, one is killed with SIGKILL and leaves its Fast DDS segment behind; the
sweep that `make stop` and every lab's start run removes that one and keeps the other.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from own_shm import domain_env, run_in_own_shm

pytestmark = [pytest.mark.ros]

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
    with domain_env() as env:
        yield env


def test_a_killed_nodes_segment_is_swept_and_a_live_nodes_kept(env: dict[str, str]) -> None:
    seen = run_in_own_shm(SCENARIO, NODE, env=env, timeout=120)
    assert len(seen["both"]) == 2, seen  # a segment for each node
    assert seen["left"] == seen["both"], "SIGKILL left no segment: nothing to test"
    assert seen["first"] == 1 and len(seen["kept"]) == 1, seen  # the killed node's went
    assert seen["second"] == 1 and seen["end"] == [], seen  # the one kept was the live node's
