"""Start the simulated world from a notebook, once per session: `start_world()`.

Lesson 3 calls it. Inside a lab (`make lab`) the world belongs to the lab: every call, shown
or not, whatever real-time factor it asks for, attaches to the lab's one world (changing its
real-time factor in place, in one printed line), so every notebook of the lab shows and drives
the same robot on one clock. Elsewhere the simulation (serving its 3D view) is a child of
the course session and ends with it (or with the kernel, however it dies).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from ..config.simulation import SimulationSettings, load_simulation_settings
from ..core.errors import CourseError
from ..sim.launcher import start_world_processes
from .world import World, _worlds, _worlds_lock

__all__ = ["start_world"]


def _own_world(
    session: Any,
    settings: SimulationSettings,
    config: Path | None,
    show: bool,
    real_time_factor: float | None,
    timeout: float,
) -> World:
    process, viewer = start_world_processes(
        session.spawn,
        config=config,
        show=show,
        real_time_factor=real_time_factor,
        timeout=timeout,
    )
    world = World(session, settings, process, viewer)
    try:
        world.wait_for_odom(timeout=timeout)
    except BaseException:
        world.stop(quiet=True)
        raise
    return world


def _lab_world(
    session: Any, settings: SimulationSettings, config: Path | None, client: Any, timeout: float
) -> World:
    """Attach to the lab's world, which the lab starts on its first request."""
    from ..lab.remote import LabProcess
    from ..viz.viewer import Viewer

    path = str(config.resolve()) if config is not None else None
    answer = client.request("world.ensure", config=path, timeout=timeout)
    if answer.get("note"):
        print(answer["note"])
    sim = LabProcess("mujoco_sim", answer["sim"]["tag"], client)
    view = answer["viewer"]
    viewer = Viewer(LabProcess("meshcat", view["tag"], client), view["zmq_url"], view["port"])
    world = World(session, settings, sim, viewer, shared=True)
    world.wait_for_odom(timeout=timeout)
    return world


def _set_lab_real_time_factor(world: World, factor: float) -> None:
    """Change the lab's world to `factor` in place (never a second world); say so if it did."""
    from ..ros2.api import nodes_and_params as api

    before = api.param_get("/mujoco", "real_time_factor").value
    if before == factor:
        return
    world.set_parameter("real_time_factor", float(factor))
    print(
        f"Set the lab's simulation to real_time_factor {factor:g} (it was {before:g}): "
        "every notebook of this lab shares that world."
    )


def _attached(session: Any) -> World | None:
    """Return this session's world if it still runs (a lab's: and is still the lab's one)."""
    world = _worlds.get(id(session))
    if world is not None and not world.alive:
        if world.shared:
            world.detach()  # the lab restarts its world itself, and says why
        else:
            world.stop(quiet=True)  # a crashed simulation: end its viewer too, then start afresh
        return None
    return world


def start_world(
    session: Any = None,
    *,
    show: bool = True,
    config: str | Path | None = None,
    real_time_factor: float | None = None,
    timeout: float = 30.0,
) -> World:
    """Start the simulated TurtleBot3 world (once per session, or the lab's) and show it.

    Args:
        session: the course session; the process's own one if None.
        show: start the meshcat view and display it in the current cell.
        config: simulation YAML; config/simulation.yaml if None.
        real_time_factor: override the config's (0 = as fast as possible, for tests);
            inside a lab the lab's world is set to it in place.
        timeout: seconds to wait for the world's first /odom.
    """
    from ..lab import machine_client
    from ..session.session import get_session

    session = session or get_session()
    path = Path(config) if config is not None else None
    settings = load_simulation_settings(path)  # a ConfigError surfaces here, in the kernel
    rtf = real_time_factor
    if rtf is not None and not (rtf >= 0 and math.isfinite(rtf)):
        raise CourseError(
            f"real_time_factor must be 0 or more, got {real_time_factor}",
            hint="use 1.0 for real time, 0 for as fast as possible.",
        )
    client = machine_client()
    with _worlds_lock:
        world = _attached(session)
        if world is not None and client is not None:
            # the lab may have restarted its world (another notebook asked for another config)
            world.detach()
            world = None
        if world is None:
            if client is not None:
                world = _lab_world(session, settings, path, client, timeout)
            else:
                world = _own_world(session, settings, path, show, real_time_factor, timeout)
            _worlds[id(session)] = world
    if client is not None and rtf is not None:
        _set_lab_real_time_factor(world, rtf)
    if show and world.viewer is not None:
        world.show()
    return world
