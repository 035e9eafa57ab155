"""MuJoCo's OpenGL backend, loaded by the camera's first frame rather than with mujoco.

`import mujoco` loads the backend MUJOCO_GL names (EGL: PyOpenGL, about 3 MiB), and most worlds
never render: nothing subscribes to the camera in the lessons.
"""

from __future__ import annotations

import importlib
import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import mujoco

__all__ = ["defer", "renderer"]

_ENV = "MUJOCO_GL"
_DEFERRED = "disable"  # mujoco's own value for "load no backend"
_wanted: str | None = None  # the backend to load at the first frame, once deferred


def defer(default: str = "egl") -> None:
    """Before mujoco is imported: load no backend now, and MUJOCO_GL's (or `default`) later."""
    global _wanted
    _wanted = os.environ.get(_ENV, default)
    os.environ[_ENV] = _DEFERRED


def renderer(model: mujoco.MjModel, height: int, width: int) -> mujoco.Renderer:
    """Return mujoco's offscreen renderer, on the backend `defer` kept (loaded the first time)."""
    import mujoco
    from mujoco.rendering.classic import gl_context

    if _wanted is not None and os.environ.get(_ENV) == _DEFERRED:
        os.environ[_ENV] = _wanted
        importlib.reload(gl_context)  # the Renderer reads gl_context.GLContext when it is made
    return mujoco.Renderer(model, height, width)
