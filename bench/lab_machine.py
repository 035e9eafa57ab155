"""A lab is one ROS 2 machine: a second lesson's time to its robot, and a lab's memory.

Run: .venv/bin/python -m bench.lab_machine
Starts a real lab as `make lab` does (headless), then three kernels with the lab's environment
(as JupyterLab gives its kernels): lesson 3 starts the world, lesson 7 attaches to it and
drives, lesson 6 runs the tutorial node. Prints the time from lesson 7's `start(7)` and
`lesson.world()` to its robot answering on /odom, and the RSS of the whole lab.
"""

from __future__ import annotations

import psutil

from bench._labs import LabKernel, start_lab

OPEN = "from course_lib.lessons import start\nlesson = start({n})\nworld = lesson.world()"


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
    lab = start_lab()
    kernels: list[LabKernel] = []
    try:
        kernels = [LabKernel(lab) for _ in range(3)]
        three, seven, six = kernels
        first = three.run(OPEN.format(n=3))
        second = seven.run(OPEN.format(n=7))
        seven.run(
            "%ros2 run parameter_tests param_vel\n%ros2 param set /param_vel_node velocity 0.2"
        )
        seven.run("lesson.drive_for(2.0)")
        six.run(OPEN.format(n=6) + "\n%ros2 run parameter_tests param_vel")
        memory = _rss([lab.pid, *(k.pid for k in kernels)])
    finally:
        for kernel in kernels:
            kernel.shutdown()
        lab.stop()
    print(f"{'first lesson: start(3) + world() (starts the lab world)':<58} {first:6.2f} s")
    print(f"{'second lesson: start(7) + world() to its robot answering':<58} {second:6.2f} s")
    label = "RSS of a lab with lessons 3, 6 and 7 open (all processes)"
    print(f"{label:<58} {memory / 2**20:6.0f} MiB")


if __name__ == "__main__":
    main()
