"""Stream the simulation's body poses to a running meshcat server (used by the sim process).

A frame's poses (the moving bodies and the TF frames) go as one message, only while a browser
watches the view (the server says how many do) and only when the robot moved since the last
frame sent; with nobody watching, the server is asked every `probe_period_s` whether someone
does now (it keeps the latest poses for a browser that connects in between). A server in this
process (`serve_in_thread`, the simulation's `--serve-view`) is handed the poses directly:
the physics loop neither waits for its reply nor asks it who watches.
"""

from __future__ import annotations

import contextlib
import time
from typing import Any

import mujoco
import numpy as np
import umsgpack
import zmq
from meshcat.commands import Delete
from meshcat.path import Path

from ...viz.scene import ROOT, body_paths, camera_commands, moving_bodies, scene_commands
from ...viz.server import POSES_COMMAND, WATCHERS_COMMAND, ThreadedServer
from ..world.frames import robot_frames
from .tf_frames import TF_ROOT, TfView

__all__ = ["LiveView", "ServerWindow"]

_TIMEOUT_MS = 2000
_PROBE_PERIOD_S = 0.25  # how soon a browser that connects gets the robot moving
_STILL = 1e-6  # metres or radians: a pose that moved less than this is not sent again
_FLOAT32_ARRAY = 0x17  # the msgpack extension meshcat's browser side reads as a Float32Array


class ServerWindow:
    """The zmq side of a meshcat server, with timeouts.

    meshcat's own ViewerWindow blocks for ever on a server that stopped answering, prints in
    its constructor, and offers no public way to set socket options; this one owns its socket
    and speaks the same three-frame protocol (type, path, msgpack of `command.lower()`).
    """

    def __init__(self, zmq_url: str, timeout_ms: int = _TIMEOUT_MS) -> None:
        self.zmq_url = zmq_url
        self.socket: zmq.Socket[bytes] = zmq.Context.instance().socket(zmq.REQ)
        self.socket.setsockopt(zmq.RCVTIMEO, timeout_ms)
        self.socket.setsockopt(zmq.SNDTIMEO, timeout_ms)
        self.socket.setsockopt(zmq.LINGER, 0)
        self.socket.connect(zmq_url)

    def send(self, command: Any) -> None:
        """Send one meshcat command and wait for the server's reply (zmq.Again on timeout)."""
        data = command.lower()
        self.socket.send_multipart(
            [data["type"].encode(), data["path"].encode(), umsgpack.packb(data)]
        )
        self.socket.recv()

    def request(self, *frames: bytes) -> bytes:
        """Send one multipart request and return the server's reply (zmq.Again on timeout)."""
        self.socket.send_multipart(list(frames))
        return self.socket.recv()

    def close(self) -> None:
        """Close the socket (no message is kept)."""
        self.socket.close(linger=0)


class LiveView:
    """Draw the model and its TF frames once, then send the moving poses on `update`.

    `zmq_url` is the server's command socket; `local` the same server when it runs in this
    process, which then takes each frame's poses without a round trip.
    """

    def __init__(
        self,
        zmq_url: str,
        model: mujoco.MjModel,
        data: mujoco.MjData,
        *,
        probe_period_s: float = _PROBE_PERIOD_S,
        local: ThreadedServer | None = None,
    ) -> None:
        self.zmq_url = zmq_url
        self.probe_period_s = probe_period_s
        self.local = local
        self.window = ServerWindow(zmq_url)
        paths = body_paths(model)
        self._moving = moving_bodies(model)
        self.updates = 0  # frames sent
        self.watchers = 0  # browsers connected, as the server last said
        self.failed = False
        self._misses = 0
        self._retry_at = 0.0
        self._next_probe = 0.0
        self._sent_qpos: np.ndarray | None = None
        self.frames = TfView(model, robot_frames(model))
        self._paths = [paths[b].lower() for b in self._moving] + [
            path.lower() for path, _ in self.frames.update_poses(data)
        ]
        for command in [
            Delete(Path(ROOT)),  # what an earlier world of this server drew
            Delete(Path(TF_ROOT)),
            *scene_commands(model, data),
            *self.frames.draw_commands(),
            *self.frames.update_commands(data),
            *camera_commands(),
        ]:
            self.window.send(command)

    def poses(self, data: mujoco.MjData) -> bytes:
        """Return one frame's poses as the server's `set_transforms` message (msgpack)."""
        bodies = np.zeros((len(self._moving), 4, 4))
        bodies[:, :3, :3] = data.xmat[self._moving].reshape(-1, 3, 3)
        bodies[:, :3, 3] = data.xpos[self._moving]
        bodies[:, 3, 3] = 1.0
        frames = [matrix for _, matrix in self.frames.update_poses(data)]
        matrices = np.concatenate([bodies, np.asarray(frames)]).transpose(0, 2, 1)  # by column
        return umsgpack.packb(
            {
                "type": POSES_COMMAND.decode(),
                "paths": self._paths,
                "matrices": umsgpack.Ext(_FLOAT32_ARRAY, matrices.astype(np.float32).tobytes()),
            }
        )

    def update(self, data: mujoco.MjData) -> bool:
        """Send the poses if a browser watches and they changed; False while the server does
        not answer.

        A busy server (several views open on a loaded machine) may miss the timeout once: the
        request socket is then replaced, so the view catches up instead of freezing for good.
        """
        if self.local is not None:
            return self._offer(data, self.local)
        now = time.monotonic()
        if now < self._retry_at:
            return False
        try:
            if not self.watchers:
                if now < self._next_probe:
                    return True
                self._next_probe = now + self.probe_period_s
                self.watchers = int(self.window.request(WATCHERS_COMMAND))
            if self.watchers and self._moved(data.qpos):
                self.watchers = int(self.window.request(POSES_COMMAND, b"", self.poses(data)))
                self._sent(data)
        except zmq.ZMQError:
            self.failed = True
            self._misses += 1  # back off, so a server that is gone stalls the physics rarely
            self._retry_at = time.monotonic() + min(30.0, 0.5 * 2**self._misses)
            self.close()
            self.window = ServerWindow(self.zmq_url)  # a timed-out REQ socket cannot send again
            return False
        self.failed, self._misses = False, 0
        return True

    def _offer(self, data: mujoco.MjData, server: ThreadedServer) -> bool:
        """Hand the poses to a server of this process if a browser watches and they changed."""
        self.watchers = server.watchers
        if self.watchers and self._moved(data.qpos):
            if not server.offer_poses(self.poses(data)):
                self.failed = True
                return False
            self._sent(data)
        return True

    def _sent(self, data: mujoco.MjData) -> None:
        """Record a frame sent: the pose the next frame is compared with."""
        self._sent_qpos = data.qpos.copy()
        self.updates += 1

    def _moved(self, qpos: np.ndarray) -> bool:
        sent = self._sent_qpos
        return sent is None or float(np.max(np.abs(qpos - sent))) > _STILL

    def close(self) -> None:
        """Close the connection to the server."""
        with contextlib.suppress(Exception):
            self.window.close()
