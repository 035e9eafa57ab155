"""What a notebook cell shows: the magics, widgets, the world handle, live outputs.

Lesson 3 starts the simulated world with `start_world()`, which returns a `World`.
"""

from __future__ import annotations

from typing import Any

__all__ = ["World", "start_world"]


def __getattr__(name: str) -> Any:
    if name == "World":
        from .world import World

        return World
    if name == "start_world":
        from .world_start import start_world

        return start_world
    raise AttributeError(name)
