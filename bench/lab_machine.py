"""A lab is one ROS 2 machine: a second lesson's time to its robot, and a lab's memory.

Run: .venv/bin/python -m bench.lab_machine
Starts a real lab as `make lab` does (headless), then three kernels with the lab's environment
(as JupyterLab gives its kernels): lesson 3 starts the world, lesson 7 attaches to it and
drives, lesson 6 runs the tutorial node. Prints the time from lesson 7's `start(7)` and
`lesson.world()` to its robot answering on /odom, and the RSS of the whole lab.
"""

from __future__ import annotations

import re
import sys
import time

import psutil
from jupyter_client.manager import KernelManager

from course_lib.machine.protocol import SOCKET_ENV
from course_lib.paths import REPO_ROOT, runtime_dir
from course_lib.processes import spawn
from course_lib.testing import independent_env

OPEN = "from course_lib.lessons import start\nlesson = start({n})\nworld = lesson.world()"


def _start_lab() -> tuple[object, dict[str, str]]:
    argv = [sys.executable, "-m", "course_lib", "lab", "--no-browser", "--ServerApp.port=0"]
    lab = spawn(argv, name="jupyterlab", env=independent_env(), cwd=REPO_ROOT, merge_stderr=True)
    if lab.wait_for_line(r"http://127\.0\.0\.1:\d+/lab", 90) is None:
        raise SystemExit(f"the lab did not start:\n{lab.text()[-2000:]}")
    domain = re.search(r"ROS_DOMAIN_ID=(\d+)", lab.text())[1]  # type: ignore[index]
    socket = runtime_dir() / f"lab-{lab.pid}.sock"
    env = independent_env(ROS_DOMAIN_ID=domain, COURSE_LAB="1", **{SOCKET_ENV: str(socket)})
    return lab, env


def _kernel(env: dict[str, str]) -> tuple[KernelManager, object]:
    manager = KernelManager(kernel_name="python3")
    manager.start_kernel(env=env, cwd=str(REPO_ROOT))
    client = manager.blocking_client()
    client.start_channels()
    client.wait_for_ready(timeout=60)
    return manager, client


def _run(client: object, code: str) -> float:
    started = time.monotonic()
    reply = client.execute_interactive(code, timeout=120, output_hook=lambda _m: None)  # type: ignore[attr-defined]
    if reply["content"]["status"] != "ok":
        raise SystemExit(f"cell failed: {code}\n{reply['content']}")
    return time.monotonic() - started


def _rss(pids: list[int]) -> int:
    total = 0
    for pid in pids:
        try:
            root = psutil.Process(pid)
            total += sum(p.memory_info().rss for p in [root, *root.children(recursive=True)])
        except psutil.NoSuchProcess:
            continue
    return total


def main() -> None:
    lab, env = _start_lab()
    kernels = []
    try:
        kernels = [_kernel(env) for _ in range(3)]
        (_, three), (_, seven), (_, six) = kernels
        first = _run(three, OPEN.format(n=3))
        second = _run(seven, OPEN.format(n=7))
        _run(
            seven,
            "%ros2 run parameter_tests param_vel\n%ros2 param set /param_vel_node velocity 0.2",
        )
        _run(seven, "lesson.drive_for(2.0)")
        _run(six, OPEN.format(n=6) + "\n%ros2 run parameter_tests param_vel")
        pids = [lab.pid, *(m.provisioner.process.pid for m, _ in kernels)]  # type: ignore[union-attr]
        memory = _rss(pids)
    finally:
        for manager, client in kernels:
            client.stop_channels()  # type: ignore[attr-defined]
            manager.shutdown_kernel(now=True)
        lab.stop(timeout=15.0)
    print(f"{'first lesson: start(3) + world() (starts the lab world)':<58} {first:6.2f} s")
    print(f"{'second lesson: start(7) + world() to its robot answering':<58} {second:6.2f} s")
    label = "RSS of a lab with lessons 3, 6 and 7 open (all processes)"
    print(f"{label:<58} {memory / 2**20:6.0f} MiB")


if __name__ == "__main__":
    main()
