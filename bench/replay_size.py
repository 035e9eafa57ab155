"""A driving lesson's replay: page bytes and save time for a 30 s drive (lesson 7's shape).

The run is what a lesson records (30 poses a simulated second) and the speed plot's samples
(one per /odom message); the save is what `lesson.save_replay()` and the self-check do after
the recording: the plot's SVG, the frames, the page, written atomically. No ROS: the poses come
from the in-process simulation, so the figures are the saving's alone.
"""

from __future__ import annotations

import math
import statistics
import tempfile
import time
from pathlib import Path

from course_lib.config.simulation import load_simulation_settings
from course_lib.lessons.replay.run import FPS, _model
from course_lib.sim.view.run_log import PoseSample, replay_frames
from course_lib.sim.world.model import WHEEL_JOINTS
from course_lib.sim.world.physics import Simulation
from course_lib.viz.replay import write_replay
from course_lib.viz.speed_svg import speed_svg

DRIVE_S = 30.0
PLAN = [(0.0, 0.0, 2.0), (0.2, 0.0, 12.0), (0.2, 0.5, 6.0), (0.0, 0.0, 10.0)]


def recorded_run() -> tuple[list[PoseSample], list[tuple[float, float]]]:
    """Return the poses (FPS a second) and /odom speed samples of a planned 30 s drive."""
    odom_hz = load_simulation_settings().rates.odom_hz
    sim = Simulation()
    wheel_adr = [sim.model.joint(j).qposadr[0] for j in WHEEL_JOINTS]
    poses, speeds = [], []
    step = 1.0 / odom_hz
    for linear, angular, seconds in PLAN:
        sim.command(linear, angular)
        for _ in range(round(seconds * odom_hz)):
            sim.run_for(step)
            q = sim.data.qpos
            speed = math.hypot(sim.data.qvel[0], sim.data.qvel[1])
            speeds.append((sim.time, speed))
            if not poses or sim.time >= poses[-1].time_s + 1.0 / FPS - 1e-9:
                wheels = (float(q[wheel_adr[0]]), float(q[wheel_adr[1]]))
                poses.append(PoseSample(sim.time, tuple(float(v) for v in q[:7]), wheels, speed))
    return poses, speeds


def main() -> None:
    poses, speeds = recorded_run()
    marks = [(2.0, "velocity := 0.2"), (20.0, "velocity := 0")]
    settings = load_simulation_settings()
    _model(settings)  # built once per kernel (cached); reported separately below
    started = time.perf_counter()
    _model.cache_clear()
    _model(settings)
    model_ms = (time.perf_counter() - started) * 1000
    times, sizes = [], []
    with tempfile.TemporaryDirectory() as folder:
        for n in range(5):
            started = time.perf_counter()
            model = _model(settings)
            svg = speed_svg(speeds, marks)
            path = write_replay(
                Path(folder) / f"run{n}.html", model, replay_frames(model, poses), plot_svg=svg
            )
            times.append((time.perf_counter() - started) * 1000)
            sizes.append(path.stat().st_size)
        bare = write_replay(Path(folder) / "bare.html", model, replay_frames(model, poses))
        bare_size = bare.stat().st_size
    print(f"run: {DRIVE_S:.0f} s simulated, {len(poses)} poses, {len(speeds)} speed samples")
    print(f"page: {sizes[-1]:,} bytes ({sizes[-1] - bare_size:,} of them the speed plot)")
    print(f"save: median {statistics.median(times):.0f} ms, max {max(times):.0f} ms (5 saves)")
    print(f"model build, first save of a kernel only: {model_ms:.0f} ms")


if __name__ == "__main__":
    main()
