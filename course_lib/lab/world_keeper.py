"""The lab's one simulated world and its 3D view, started on the first lesson's request.

Lives in the `make lab` process, so the robot belongs to the lab, not to the kernel that first
asked for it: shutting one notebook down never takes the robot away from another.
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

from ..processes.children import ChildProcess
from ..processes.orphans import owner_tag
from ..sim.launcher import Spawner, start_world_processes

__all__ = ["WorldKeeper"]

_TAIL_LINES = 8


class WorldKeeper:
    """Start the world once, restart it when it died, describe it to the kernels."""

    def __init__(self, spawn: Spawner) -> None:
        self._spawn = spawn
        self._lock = threading.Lock()
        self._sim: ChildProcess | None = None
        self._viewer: Any = None
        self._config: str | None = None
        self._last: ChildProcess | None = None

    def _why_restart(self, config: str | None) -> str:
        if self._sim is None:
            return ""
        if not self._sim.alive:
            return f"The simulation had stopped (exit code {self._sim.returncode}); restarted it."
        if config != self._config:
            return f"Restarted the simulation with {config or 'config/simulation.yaml'}."
        return ""

    def ensure(self, config: str | None, timeout: float = 30.0) -> dict[str, Any]:
        """Make sure the world runs with `config` (None: the course's); describe it."""
        with self._lock:
            note = self._why_restart(config)
            if note:
                self._stop_locked()
            started = self._sim is None
            if started:
                self._sim, self._viewer = start_world_processes(
                    self._spawn,
                    config=Path(config) if config else None,
                    show=True,
                    real_time_factor=None,
                    timeout=timeout,
                )
                self._config = config
            return {"started": started, "note": note, **self._describe()}

    def _describe(self) -> dict[str, Any]:
        assert self._sim is not None and self._viewer is not None
        viewer = self._viewer
        return {
            "config": self._config,
            "sim": {"tag": owner_tag(self._sim.pid)},
            "viewer": {
                "tag": owner_tag(viewer.process.pid),
                "port": viewer.port,
                "zmq_url": viewer.zmq_url,
            },
        }

    def status(self) -> dict[str, Any]:
        """Say whether the world runs, how it ended, and its last lines."""
        with self._lock:
            sim = self._sim or self._last
            if sim is None:
                return {"running": False, "returncode": None, "tail": []}
            tail = [line.text for line in sim.lines[-_TAIL_LINES:]]
            running = sim.alive and sim is self._sim
            return {
                "running": running,
                "config": self._config if running else None,
                "returncode": sim.returncode,
                "tail": tail,
            }

    def stop(self) -> None:
        """Stop the world and its view (a learner's `world.stop()`, the lab ending); idempotent."""
        with self._lock:
            self._stop_locked()

    def _stop_locked(self) -> None:
        if self._sim is not None:
            self._sim.stop()
            self._last = self._sim  # its exit code and last lines stay readable
        if self._viewer is not None:
            self._viewer.stop()
        self._sim = self._viewer = None
