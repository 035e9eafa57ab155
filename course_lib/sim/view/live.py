"""Stream the simulation's body poses to a running meshcat server (used by the sim process)."""

from __future__ import annotations

import contextlib
import time
from typing import Any

import meshcat
import mujoco
import umsgpack
import zmq

from ...viz.scene import body_paths, body_transform, camera_commands, moving_bodies, scene_commands
from ..world.frames import robot_frames
from .tf_frames import TfView

__all__ = ["LiveView", "ServerWindow"]

_TIMEOUT_MS = 2000


class ServerWindow:
    """The zmq side of a meshcat server, with timeouts (a `window` for meshcat.Visualizer).

    meshcat's own ViewerWindow blocks for ever on a server that stopped answering, prints in
    its constructor, and offers no public way to set socket options; this one owns its socket
    and speaks the same three-frame protocol (type, path, msgpack of `command.lower()`).
    """

    def __init__(self, zmq_url: str, timeout_ms: int = _TIMEOUT_MS) -> None:
        self.zmq_url = zmq_url
        self.socket = zmq.Context.instance().socket(zmq.REQ)
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

    def close(self) -> None:
        """Close the socket (no message is kept)."""
        self.socket.close(linger=0)


class LiveView:
    """Draw the model and its TF frames once, then send the moving transforms on `update`."""

    def __init__(self, zmq_url: str, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.zmq_url = zmq_url
        self.window = ServerWindow(zmq_url)
        self.visualizer = meshcat.Visualizer(window=self.window)
        self._paths = body_paths(model)
        self._moving = moving_bodies(model)
        self.updates = 0
        self.failed = False
        self._misses = 0
        self._retry_at = 0.0
        self.frames = TfView(model, robot_frames(model))
        self.visualizer["mujoco"].delete()
        self.visualizer["tf"].delete()
        for command in [
            *scene_commands(model, data),
            *self.frames.draw_commands(),
            *self.frames.update_commands(data),
            *camera_commands(),
        ]:
            self.window.send(command)

    def update(self, data: mujoco.MjData) -> bool:
        """Send the moving bodies' poses; False while the server does not answer.

        A busy server (several views open on a loaded machine) may miss the timeout once: the
        request socket is then replaced, so the view catches up instead of freezing for good.
        """
        if time.monotonic() < self._retry_at:
            return False
        try:
            for body in self._moving:
                self.window.send(
                    meshcat.commands.SetTransform(body_transform(data, body), self._paths[body])
                )
            for command in self.frames.update_commands(data):
                self.window.send(command)
        except zmq.ZMQError:
            self.failed = True
            self._misses += 1  # back off, so a server that is gone stalls the physics rarely
            self._retry_at = time.monotonic() + min(30.0, 0.5 * 2**self._misses)
            self.close()
            self.window = ServerWindow(self.zmq_url)  # a timed-out REQ socket cannot send again
            return False
        self.failed, self._misses = False, 0
        self.updates += 1
        return True

    def close(self) -> None:
        """Close the connection to the server."""
        with contextlib.suppress(Exception):
            self.window.close()
