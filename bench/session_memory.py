"""Peak memory of a whole course session: a real kernel running lesson 7's steps.

Run: .venv/bin/python -m bench.session_memory
Sums the RSS of the kernel and every process below it (simulation serving the 3D view, the
learner's node), sampled every 50 ms while the lesson runs; shared pages count once per process.
"""

from __future__ import annotations

import os
import threading

import psutil
from jupyter_client.manager import KernelManager
from suite_env import TEST_ENV

from course_lib.core.paths import REPO_ROOT

LESSON = """
%load_ext course_lib.notebook.magics
from course_lib.session.session import get_session
from course_lib.notebook import start_world
session = get_session()
node = session.run("parameter_tests", "param_vel")
world = start_world(session, show=True)
import time
deadline = time.monotonic() + 15
while time.monotonic() < deadline and "/param_vel_node" not in __import__(
        "course_lib.notebook.magics", fromlist=["run_line"]).run_line("node list").output.stdout:
    time.sleep(0.05)
%ros2 param set /param_vel_node velocity 0.2
world.wait_for_odom(lambda r: r.linear_mps > 0.15, 10)
world.wait_sim_time(world.odom().time_s + 3.0)
"""


def _tree_rss(pid: int) -> dict[str, int]:
    """Return RSS in bytes of `pid` and its descendants, by command name."""
    sizes: dict[str, int] = {}
    try:
        root = psutil.Process(pid)
        procs = [root, *root.children(recursive=True)]
    except psutil.NoSuchProcess:
        return sizes
    for proc in procs:
        try:
            cmd = " ".join(proc.cmdline()[1:3]) or proc.name()
            sizes[cmd] = sizes.get(cmd, 0) + proc.memory_info().rss
        except psutil.NoSuchProcess:
            continue
    return sizes


def main() -> None:
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_DOMAIN_ID",)}
    env.update(TEST_ENV)
    manager = KernelManager(kernel_name="python3")
    manager.start_kernel(env=env, cwd=str(REPO_ROOT))
    client = manager.blocking_client()
    client.start_channels()
    peak: dict[str, int] = {}
    done = threading.Event()

    def sample() -> None:
        pid = manager.provisioner.pid  # type: ignore[union-attr]
        while not done.wait(0.05):
            sizes = _tree_rss(pid)
            if sum(sizes.values()) > sum(peak.values()):
                peak.clear()
                peak.update(sizes)

    try:
        client.wait_for_ready(timeout=60)
        sampler = threading.Thread(target=sample, daemon=True)
        sampler.start()
        reply = client.execute_interactive(LESSON, timeout=90, output_hook=lambda _m: None)
        assert reply["content"]["status"] == "ok", reply["content"]
    finally:
        done.set()
        client.stop_channels()
        manager.shutdown_kernel(now=True)
    total = sum(peak.values())
    print(f"{'peak RSS of a lesson-7 session (kernel + children)':<48} {total / 2**20:7.0f} MiB")
    for cmd, size in sorted(peak.items(), key=lambda kv: -kv[1]):
        print(f"    {size / 2**20:7.0f} MiB  {cmd[:70]}")


if __name__ == "__main__":
    main()
