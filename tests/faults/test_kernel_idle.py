"""An idle lesson's live plot costs its kernel nothing (issue 23): with lesson 7's world and node
running and the robot standing still, opening the live speed plot adds (almost) no CPU time to
the kernel over 5 s idle (read from /proc, not timed): no redraw without motion."""

from __future__ import annotations

import os
import time

import pytest
from jupyter_kernels import Kernel

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

IDLE_S = 5.0
# CPU seconds the live plot may add over IDLE_S. The world handle's own /odom subscription
# (rclpy's executor, 50 messages a second) takes ~0.2 s with or without it; the old plot's
# redraws of a still robot, twice a second, added ~0.45 s more (measured under load).
PLOT_BOUND_S = 0.1
TICKS = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid: int) -> float:
    """Return the user + system CPU seconds of `pid` (from /proc/PID/stat)."""
    with open(f"/proc/{pid}/stat") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / TICKS


def idle_cpu(kernel: Kernel) -> float:
    """Return the kernel's CPU seconds over IDLE_S while no cell runs."""
    time.sleep(2.0)  # the last cell's own work has ended
    before = cpu_seconds(kernel.pid)
    time.sleep(IDLE_S)
    return cpu_seconds(kernel.pid) - before


def test_a_live_plot_of_a_still_robot_costs_its_kernel_nothing(start_kernel) -> None:
    kernel: Kernel = start_kernel()
    kernel.ok(
        "from course_lib.lessons import start\nlesson = start(7)\n"
        "world = lesson.world(show=False)",
        timeout=120,
    )
    kernel.ok("%ros2 run parameter_tests param_vel")
    kernel.ok("world.wait_for_odom(lambda r: abs(r.linear_mps) < 1e-3)")
    without = idle_cpu(kernel)
    kernel.ok("plot = lesson.speed_plot()")
    with_plot = idle_cpu(kernel)
    print(f"idle kernel over {IDLE_S:g} s: {without:.3f} CPU s, {with_plot:.3f} with the plot")
    assert with_plot - without < PLOT_BOUND_S, (
        f"the live plot of a still robot used {with_plot - without:.2f} CPU s in {IDLE_S:g} s"
    )
    kernel.ok("plot.close()")
