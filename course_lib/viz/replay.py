"""Recorded replays: a run's poses as a standalone, offline HTML page (meshcat animation).

The page embeds meshcat's viewer script and the scene, so it plays without a kernel or a
server. The same frames always give the same bytes (object ids are derived from paths).
"""

from __future__ import annotations

import base64
import html
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import meshcat
import mujoco
import umsgpack
from meshcat.animation import Animation, AnimationFrameVisualizer
from meshcat.commands import SetAnimation

from .scene import body_paths, body_transform, camera_commands, moving_bodies, scene_commands

__all__ = ["ReplayFrame", "replay_html", "write_replay"]

# meshcat.servers.zmqserver has the same path, but importing it warns (zmq.eventloop).
VIEWER_ROOT = Path(meshcat.__file__).parent / "viewer" / "dist"


@dataclass(frozen=True)
class ReplayFrame:
    """The model's joint positions (qpos) at a simulated time."""

    time_s: float
    qpos: tuple[float, ...]


def _animation(model: mujoco.MjModel, frames: Sequence[ReplayFrame], fps: int) -> Animation:
    data = mujoco.MjData(model)
    paths = body_paths(model)
    animation = Animation(default_framerate=fps)
    start = frames[0].time_s
    seen: set[int] = set()
    for frame in frames:
        index = round((frame.time_s - start) * fps)
        if index in seen:
            continue
        seen.add(index)
        data.qpos[:] = frame.qpos
        mujoco.mj_kinematics(model, data)
        for body in moving_bodies(model):
            at = AnimationFrameVisualizer(animation, paths[body], index)
            at.set_transform(body_transform(data, body))
    return animation


def _command_js(command: Any) -> str:
    payload = base64.b64encode(umsgpack.packb(command.lower())).decode("ascii")
    return f'viewer.handle_command_bytearray(bytes("{payload}"));\n'


def replay_html(
    model: mujoco.MjModel, frames: Sequence[ReplayFrame], *, fps: int = 30, title: str = "Replay"
) -> str:
    """Return a standalone HTML page that plays `frames` of `model` in meshcat."""
    if not frames:
        raise ValueError("a replay needs at least one frame")
    data = mujoco.MjData(model)
    data.qpos[:] = frames[0].qpos
    mujoco.mj_kinematics(model, data)
    commands = [*scene_commands(model, data), *camera_commands()]
    commands.append(SetAnimation(_animation(model, frames, fps), play=True, repetitions=1))
    script = (VIEWER_ROOT / "main.min.js").read_text(encoding="utf-8")
    body = "".join(_command_js(c) for c in commands)
    return (
        "<!DOCTYPE html>\n<html>\n<head><meta charset=utf-8>"
        f"<title>{html.escape(title)}</title>\n<style>body {{margin: 0}} #meshcat-pane "
        "{width: 100vw; height: 100vh; overflow: hidden}</style></head>\n<body>\n"
        f'<div id="meshcat-pane"></div>\n<script>\n{script}\n</script>\n<script>\n'
        "function bytes(b64) { return Uint8Array.from(atob(b64), c => c.charCodeAt(0)); }\n"
        'var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));\n'
        f"{body}</script>\n</body>\n</html>\n"
    )


def write_replay(
    path: str | Path, model: mujoco.MjModel, frames: Sequence[ReplayFrame], *, fps: int = 30
) -> Path:
    """Write the replay page to `path` and return it."""
    target = Path(path)
    target.write_text(replay_html(model, frames, fps=fps, title=target.stem), encoding="utf-8")
    return target
