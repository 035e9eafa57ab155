"""Recorded replays: a run's poses as a standalone, offline HTML page (meshcat animation).

The page embeds meshcat's viewer script and the scene, so it plays without a kernel or a
server; a speed plot (inline SVG, `speed_svg`) may sit under the 3D view, a playhead on it
following the animation. The same frames always give the same bytes (object ids are derived
from paths).
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
import numpy as np
import umsgpack

from ..core.files.atomic_files import atomic_write
from .page_access import PANEL_JS
from .scene import body_paths, camera_commands, moving_bodies, scene_commands
from .speed_svg import PLAYHEAD_ID, PLOT_ID

__all__ = ["ReplayFrame", "replay_html", "write_replay"]

# meshcat.servers.zmqserver has the same path, but importing it warns (zmq.eventloop).
VIEWER_ROOT = Path(meshcat.__file__).parent / "viewer" / "dist"
FLOAT32_EXT = 0x17  # meshcat's msgpack extension type for a Float32Array


@dataclass(frozen=True)
class ReplayFrame:
    """The model's joint positions (qpos) at a simulated time."""

    time_s: float
    qpos: tuple[float, ...]


def _float32(values: Any) -> umsgpack.Ext:
    """Pack numbers as meshcat's Float32Array extension (decoded in the page, no parsing)."""
    return umsgpack.Ext(FLOAT32_EXT, np.asarray(values, dtype="<f4").tobytes())


def _set_animation(model: mujoco.MjModel, frames: Sequence[ReplayFrame], fps: int) -> dict:
    """Return meshcat's set_animation command: one position and one quaternion track per
    moving body, as three.js keyframe arrays (frame numbers, flat values) in Float32Arrays.

    MuJoCo gives each body's world position and quaternion directly; the arrays make the
    page compact and quick to write (a per-key map per frame costs seconds for a long run).
    """
    data = mujoco.MjData(model)
    paths, bodies = body_paths(model), moving_bodies(model)
    start = frames[0].time_s
    times: list[int] = []
    positions: list[np.ndarray] = []
    quaternions: list[np.ndarray] = []
    for frame in frames:
        index = round((frame.time_s - start) * fps)
        if times and index <= times[-1]:
            continue
        times.append(index)
        data.qpos[:] = frame.qpos
        mujoco.mj_kinematics(model, data)
        positions.append(data.xpos[bodies].copy())
        quaternions.append(data.xquat[bodies][:, [1, 2, 3, 0]].copy())  # three.js: x y z w
    at = np.asarray(times)
    pos, quat = np.stack(positions), np.stack(quaternions)
    animations = [
        {
            "path": paths[body].lower(),
            "clip": {
                "fps": fps,
                "name": "default",
                "tracks": [
                    {
                        "name": ".position",
                        "type": "vector3",
                        "times": _float32(at),
                        "values": _float32(pos[:, i].ravel()),
                    },
                    {
                        "name": ".quaternion",
                        "type": "quaternion",
                        "times": _float32(at),
                        "values": _float32(quat[:, i].ravel()),
                    },
                ],
            },
        }
        for i, body in enumerate(bodies)
    ]
    return {
        "type": "set_animation",
        "animations": animations,
        "options": {"play": False, "repetitions": 1},  # played once drawn (_PLAY_JS)
        "path": "",
    }


def _command_js(command: Any) -> str:
    lowered = command if isinstance(command, dict) else command.lower()
    payload = base64.b64encode(umsgpack.packb(lowered)).decode("ascii")
    return f'viewer.handle_command_bytearray(bytes("{payload}"));\n'


# The animation starts once the scene has been drawn twice. Started as the page loads, its clock
# would run through the first frame, which compiles the scene's shaders: on a busy machine that
# frame can outlast a short replay, which would end (and go back to its start) unseen.
_PLAY_JS = """requestAnimationFrame(function () {
  requestAnimationFrame(function () { viewer.animator.play(); });
});
"""

# A playhead on the speed plot follows the animation's time (meshcat's Animator actions).
_PLAYHEAD_JS = """(function () {
  var svg = document.getElementById("%(plot)s"), head = document.getElementById("%(head)s");
  if (!svg || !head) return;
  var t0 = +svg.getAttribute("data-t0"), t1 = +svg.getAttribute("data-t1");
  var x0 = +svg.getAttribute("data-x0"), w = +svg.getAttribute("data-width");
  function tick() {
    var s = %(start)s + viewer.animator.actions.reduce(function (m, a) {
      return Math.max(m, a.time); }, 0);
    var inside = s >= t0 && s <= t1, x = x0 + (s - t0) / (t1 - t0) * w;
    head.setAttribute("x1", x); head.setAttribute("x2", x);
    head.setAttribute("visibility", inside ? "visible" : "hidden");
    requestAnimationFrame(tick);
  }
  tick();
})();
"""
# Play / Pause, back to the start, and a time slider, always in view (meshcat's own are in its
# folded control panel). A replay that ended plays again from the start.
_CONTROLS_HTML = """<div id="replay-bar" role="group" aria-label="Replay">
<button id="replay-toggle" type="button">Pause</button>
<button id="replay-restart" type="button">From the start</button>
<label for="replay-time">Simulated time</label>
<input id="replay-time" type="range" min="0" max="%(duration)s" step="0.1" value="0">
<output id="replay-now" for="replay-time">%(start)s s</output>
</div>
"""
_CONTROLS_JS = """(function () {
  var animator = viewer.animator, start = %(start)s;
  var toggle = document.getElementById("replay-toggle");
  var restart = document.getElementById("replay-restart");
  var slider = document.getElementById("replay-time");
  var now = document.getElementById("replay-now");
  function time() { return animator.actions.reduce(function (m, a) {
    return Math.max(m, a.time); }, 0); }
  function ended() { return animator.actions.every(function (a) { return !a.isRunning(); }); }
  function running() { return animator.playing && !ended(); }
  function show() {
    var label = running() ? "Pause" : "Play";
    if (toggle.textContent !== label) toggle.textContent = label;
    if (document.activeElement !== slider) slider.value = time().toFixed(1);
    now.textContent = (start + time()).toFixed(1) + " s";
    requestAnimationFrame(show);
  }
  toggle.addEventListener("click", function () {
    if (running()) { animator.pause(); return; }
    if (ended()) animator.reset();
    animator.play();
  });
  restart.addEventListener("click", function () { animator.reset(); animator.play(); });
  slider.addEventListener("input", function () {
    if (ended()) animator.reset();  // an ended action holds its last frame: free it first
    animator.pause(); animator.seek(+slider.value);
  });
  show();
})();
"""
_NEEDS_SCRIPTS = (
    '<p id="needs-scripts">The 3D motion needs scripts: in JupyterLab click '
    "&ldquo;Trust HTML&rdquo; above it, or open this file in a web browser.</p>"
)


def replay_html(
    model: mujoco.MjModel,
    frames: Sequence[ReplayFrame],
    *,
    fps: int = 30,
    title: str = "Replay",
    plot_svg: str | None = None,
) -> str:
    """Return a standalone HTML page that plays `frames` of `model` in meshcat.

    `plot_svg` (from `speed_svg`) is shown under the 3D view, with a playhead at the
    animation's simulated time.
    """
    if not frames:
        raise ValueError("a replay needs at least one frame")
    data = mujoco.MjData(model)
    data.qpos[:] = frames[0].qpos
    mujoco.mj_kinematics(model, data)
    commands = [*scene_commands(model, data), *camera_commands()]
    commands.append(_set_animation(model, frames, fps))
    script = (VIEWER_ROOT / "main.min.js").read_text(encoding="utf-8")
    body = "".join(_command_js(c) for c in commands)
    pane_height = "calc(100vh - 3em)" if plot_svg is None else "58vh"
    timing = {
        "start": f"{frames[0].time_s:.1f}",
        "duration": f"{frames[-1].time_s - frames[0].time_s:.1f}",
    }
    plot = ""
    playhead = ""
    if plot_svg is not None:
        plot = f'<div id="plot-pane">\n{plot_svg}\n</div>\n'
        start = f"{frames[0].time_s:.4f}"
        playhead = _PLAYHEAD_JS % {"plot": PLOT_ID, "head": PLAYHEAD_ID, "start": start}
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head><meta charset=utf-8>'
        f"<title>{html.escape(title)}</title>\n<style>body {{margin: 0; background: #fff; "
        "color: #000; color-scheme: light}} #meshcat-pane "
        f"{{width: 100vw; height: {pane_height}; overflow: hidden; position: relative}} "
        "#plot-pane {text-align: center} #plot-pane svg {max-width: 100%; height: auto} "
        "#needs-scripts {position: absolute; top: 40%; width: 100%; text-align: center; "
        "font-family: sans-serif} #replay-bar {font-family: sans-serif; padding: 0.4em; "
        "display: flex; flex-wrap: wrap; gap: 0.6em; align-items: center} "
        "#replay-bar button {min-height: 2.2em} #replay-time {flex: 1; min-width: 8em}"
        "</style></head>\n<body>\n"
        f'<div id="meshcat-pane">{_NEEDS_SCRIPTS}</div>\n{_CONTROLS_HTML % timing}{plot}'
        f"<script>\n{script}\n</script>\n"
        "<script>\n"
        'document.getElementById("needs-scripts").remove();\n'
        "function bytes(b64) { return Uint8Array.from(atob(b64), c => c.charCodeAt(0)); }\n"
        'var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));\n'
        f"{body}{_PLAY_JS}{playhead}{_CONTROLS_JS % timing}{PANEL_JS}"
        "accessiblePanel(viewer, null);\n</script>\n</body>\n</html>\n"
    )


def write_replay(
    path: str | Path,
    model: mujoco.MjModel,
    frames: Sequence[ReplayFrame],
    *,
    fps: int = 30,
    plot_svg: str | None = None,
) -> Path:
    """Write the replay page to `path` atomically (never half a page) and return it."""
    target = Path(path)
    page = replay_html(model, frames, fps=fps, title=target.stem, plot_svg=plot_svg)
    return atomic_write(target, page)
