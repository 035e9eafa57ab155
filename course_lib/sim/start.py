"""Start the simulated world from a notebook, once per session: `start_world()`.

Lesson 3 calls it; the simulation and its meshcat server are children of the course session,
so they end with it (or with the kernel, however it dies).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

from ..config.simulation import SimulationSettings, load_simulation_settings
from ..errors import CourseError, ProcessStartError
from .world import World, _worlds, _worlds_lock
from .world_process import READY_TEXT

__all__ = ["start_world"]


def _start(
    session: Any,
    settings: SimulationSettings,
    config: Path | None,
    show: bool,
    real_time_factor: float | None,
    timeout: float,
) -> World:
    from ..viz.viewer import Viewer

    viewer = Viewer.start(session) if show else None
    argv = [sys.executable, "-m", "course_lib.sim"]
    if config is not None:
        argv += ["--config", str(config)]
    if real_time_factor is not None:
        argv += ["--real-time-factor", f"{real_time_factor:g}"]
    if viewer is not None:
        argv += ["--meshcat-url", viewer.zmq_url]
    process = session.spawn(argv, name="mujoco_sim")
    world = World(session, settings, process, viewer)
    if process.wait_for_line(READY_TEXT, timeout) is None:
        world.stop()
        tail = "\n".join(line.text for line in process.lines[-8:])
        raise ProcessStartError(
            f"The simulation did not start within {timeout:g} s.\n{tail}",
            hint="read the lines above; `make doctor` checks the setup.",
        )
    world.wait_for_odom(timeout=timeout)
    return world


def start_world(
    session: Any = None,
    *,
    show: bool = True,
    config: str | Path | None = None,
    real_time_factor: float | None = None,
    timeout: float = 30.0,
) -> World:
    """Start the simulated TurtleBot3 world (once per session) and show its 3D view.

    Args:
        session: the course session; the process's own one if None.
        show: start the meshcat view and display it in the current cell.
        config: simulation YAML; config/simulation.yaml if None.
        real_time_factor: override the config's (0 = as fast as possible, for tests).
        timeout: seconds to wait for the world's first /odom.
    """
    from ..session import get_session

    session = session or get_session()
    path = Path(config) if config is not None else None
    settings = load_simulation_settings(path)  # a ConfigError surfaces here, in the kernel
    rtf = real_time_factor
    if rtf is not None and not (rtf >= 0 and math.isfinite(rtf)):
        raise CourseError(
            f"real_time_factor must be 0 or more, got {real_time_factor}",
            hint="use 1.0 for real time, 0 for as fast as possible.",
        )
    with _worlds_lock:
        world = _worlds.get(id(session))
        if world is not None and not world.alive:
            world.stop()  # a crashed simulation: also end its viewer before starting afresh
            world = None
        if world is None:
            world = _start(session, settings, path, show, real_time_factor, timeout)
            _worlds[id(session)] = world
    if show and world.viewer is not None:
        world.show()
    return world
