"""Start the simulation and its meshcat viewer as two child processes, whoever owns them.

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
    """Start the viewer (if `show`) and the simulation; return (simulation, viewer or None)."""
    from ..viz.viewer import Viewer

    viewer = Viewer.start(spawn, timeout=min(timeout, 10.0)) if show else None
    argv = [sys.executable, "-m", "course_lib.sim"]
    if config is not None:
        argv += ["--config", str(config)]
    if real_time_factor is not None:
        argv += ["--real-time-factor", f"{real_time_factor:g}"]
    if viewer is not None:
        argv += ["--meshcat-url", viewer.zmq_url]
    process = spawn(argv, name="mujoco_sim")
    if process.wait_for_line(READY_TEXT, timeout) is None:
        process.stop()
        if viewer is not None:
            viewer.stop()
        tail = "\n".join(line.text for line in process.lines[-8:])
        raise ProcessStartError(
            f"The simulation did not start within {timeout:g} s.\n{tail}",
            hint="read the lines above; `make doctor` checks the setup.",
        )
    return process, viewer
