"""Start the simulation, which serves its own 3D view, as a child process of whoever owns it.

A kernel outside a lab starts them as its session's children (`notebook.world_start`); inside a
lab the lab's machine service starts them as its own (`lab.world_keeper`), so every notebook
of the lab shares one robot.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..core.errors import ProcessStartError
from ..processes.children import ChildProcess
from .world_process import READY_TEXT

__all__ = ["Spawner", "start_world_processes"]

Spawner = Callable[..., ChildProcess]  # spawn(argv, name=...) -> ChildProcess


def start_world_processes(
    spawn: Spawner,
    *,
    config: Path | None,
    show: bool,
    real_time_factor: float | None,
    timeout: float,
) -> tuple[ChildProcess, Any]:
    """Start the simulation (serving its view if `show`); return (simulation, viewer or None).

    The viewer is the simulation process itself (`--serve-view`): stopping either stops both.
    """
    from ..viz.viewer import Viewer

    argv = [sys.executable, "-m", "course_lib.sim"]
    if config is not None:
        argv += ["--config", str(config)]
    if real_time_factor is not None:
        argv += ["--real-time-factor", f"{real_time_factor:g}"]
    if show:
        argv += ["--serve-view"]
    process = spawn(argv, name="mujoco_sim")
    ready = process.wait_for_line(READY_TEXT, timeout) is not None
    viewer = Viewer.served_by(process, 1.0) if ready and show else None
    if not ready or (show and viewer is None):
        process.stop()
        tail = "\n".join(line.text for line in process.lines[-8:])
        raise ProcessStartError(
            f"The simulation did not start within {timeout:g} s.\n{tail}",
            hint="read the lines above; `make doctor` checks the setup.",
        )
    return process, viewer
