"""Runs inside a learner's kernel for bench/class_capacity.py: lesson 7's drive, measured.

`drive_window(lesson, t0, t1, gets, seed)` keeps the robot driving at the lesson's speed
between two marks on the floor (turning it round with `%ros2 param set`, as a learner would)
from now until wall time `t1`; between wall times `t0` and `t1` it times `gets`
`%ros2 param get` magics, one in each of `gets` equal slots, and samples the simulation's clock
(the /odom stamps). With a `seed`, each get comes at a random moment of its slot (a learner of
its own: learners do not type in step); with none, at the slot's start (every learner's kernel
then asks at the same instant: a burst of N commands at once). It returns one JSON line: the
real-time factor over the window, the get latencies, the top speed.
"""

from __future__ import annotations

import json
import random
import time
from typing import Any

__all__ = ["drive_window", "get_moments", "real_time_factor"]

NODE = "/param_vel_node"
TURN_AT_M = (0.0, 1.5)  # drive between these x marks (the obstacle box stands at x 2.4 m)


def real_time_factor(samples: list[tuple[float, float]]) -> float:
    """Return the least-squares slope of simulated time over wall time (pure)."""
    if len(samples) < 2:
        return float("nan")
    n = len(samples)
    mean_w = sum(w for w, _ in samples) / n
    mean_s = sum(s for _, s in samples) / n
    var = sum((w - mean_w) ** 2 for w, _ in samples)
    cov = sum((w - mean_w) * (s - mean_s) for w, s in samples)
    return cov / var if var > 0 else float("nan")


def get_moments(t0: float, t1: float, gets: int, seed: int | None) -> list[float]:
    """Return when each get is due: one in each of `gets` equal slots of [t0, t1), at a
    random moment of it (`seed`), or at its start (None) (pure)."""
    spacing = (t1 - t0) / gets
    draw = random.Random(seed)
    return [t0 + (i + (0.0 if seed is None else draw.random())) * spacing for i in range(gets)]


def drive_window(lesson: Any, t0: float, t1: float, gets: int, seed: int | None = None) -> str:
    """Drive back and forth until `t1`, timing `%ros2 param get` from `t0`; return JSON."""
    from IPython import get_ipython
    from IPython.utils.capture import capture_output

    shell = get_ipython()
    world = lesson.current_world
    speed = lesson.velocity

    def magic(line: str) -> str:
        with capture_output() as captured:
            shell.run_line_magic("ros2", line)  # the magic displays its answer
        shown = (out.data.get("text/plain", "") for out in captured.outputs)
        return captured.stdout + "".join(shown)

    heading = 1.0

    def steer() -> None:
        nonlocal heading
        x = world.odom().pose.x
        if (heading > 0 and x > TURN_AT_M[1]) or (heading < 0 and x < TURN_AT_M[0]):
            heading = -heading
            magic(f"param set {NODE} velocity {heading * speed}")

    late = max(0.0, time.time() - t0)
    while time.time() < t0:
        steer()
        time.sleep(min(0.05, max(0.0, t0 - time.time())))
    samples: list[tuple[float, float]] = []
    latencies: list[float] = []
    top = 0.0
    for due in get_moments(t0, t1, gets, seed):
        while time.time() < due:
            time.sleep(min(0.05, max(0.0, due - time.time())))
        if time.time() >= t1:
            break
        started = time.perf_counter()
        answer = magic(f"param get {NODE} velocity")
        latencies.append(time.perf_counter() - started)
        if not answer.startswith("Double value is:"):
            raise RuntimeError(f"unexpected answer to param get: {answer!r}")
        reading = world.odom()
        samples.append((time.time(), reading.time_s))
        top = max(top, abs(reading.linear_mps))
        steer()
    while time.time() < t1:
        reading = world.odom()
        samples.append((time.time(), reading.time_s))
        steer()
        time.sleep(0.1)
    return json.dumps(
        {
            "rtf": real_time_factor(samples),
            "sim_s": samples[-1][1] - samples[0][1] if samples else 0.0,
            "wall_s": samples[-1][0] - samples[0][0] if samples else 0.0,
            "gets_s": latencies,
            "top_speed": top,
            "late_s": late,
        }
    )
