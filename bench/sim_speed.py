"""Simulated seconds per wall second, headless: physics alone, and the whole world process."""

from __future__ import annotations

import re
import statistics
import sys
import time

from course_lib.session.session import Session
from course_lib.sim.world.physics import Simulation

SIM_SECONDS = 20.0


def physics_only(sense_hz: float) -> float:
    """Real-time factor of stepping, computing sensors `sense_hz` times per simulated second."""
    sim = Simulation()
    sim.command(0.2, 0.3)
    chunk = max(1, round(1.0 / (sense_hz * sim.timestep))) if sense_hz else 1000
    steps = round(SIM_SECONDS / sim.timestep)
    start = time.perf_counter()
    for tick in range(steps // chunk):
        sim.step(chunk)
        if sense_hz:
            sim.sense(scan=tick % 10 == 0)  # lidar at a tenth of the IMU's rate, as published
    return SIM_SECONDS / (time.perf_counter() - start)


def whole_process(session: Session, duration: float) -> float:
    """Real-time factor of `python -m course_lib.sim` at --real-time-factor 0, ROS included."""
    argv = [sys.executable, "-m", "course_lib.sim", "--real-time-factor", "0"]
    child = session.spawn([*argv, "--duration", f"{duration:g}"], name="sim_bench")
    line = child.wait_for_line(r"x real time\)", 120)
    assert line is not None, child.text()
    child.wait(30)
    return float(re.search(r"\(([0-9.]+)x real time", line.text).group(1))


def main() -> None:
    runs = [physics_only(0) for _ in range(3)]
    print(f"physics only (no sensors):            {statistics.median(runs):6.0f}x real time")
    runs = [physics_only(50) for _ in range(3)]
    print(f"physics + IMU 50 Hz + lidar 5 Hz:     {statistics.median(runs):6.0f}x real time")
    session = Session()
    try:
        factors = [whole_process(session, 20.0) for _ in range(3)]
    finally:
        session.close()
    print(
        f"world process, ROS publishing, no view:{statistics.median(factors):6.0f}x real time"
        f"  (goal >= 50x; 20 simulated s, median of 3)"
    )


if __name__ == "__main__":
    main()
