"""Stream the simulation's body poses to a running meshcat server (used by the sim process)."""

from __future__ import annotations

import contextlib
import io
import time

import meshcat
import mujoco
import zmq

from ..sim.frames import robot_frames
from .scene import body_paths, body_transform, camera_commands, moving_bodies, scene_commands
from .tf_frames import TfView

__all__ = ["LiveView"]

_TIMEOUT_MS = 2000


class LiveView:
    """Draw the model and its TF frames once, then send the moving transforms on `update`."""

    def __init__(self, zmq_url: str, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.zmq_url = zmq_url
        self.visualizer = self._connect()
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
            self.visualizer.window.send(command)

    def _connect(self) -> meshcat.Visualizer:
        with contextlib.redirect_stdout(io.StringIO()):  # meshcat prints in its constructor
            visualizer = meshcat.Visualizer(zmq_url=self.zmq_url)
        socket = visualizer.window.zmq_socket
        socket.setsockopt(zmq.RCVTIMEO, _TIMEOUT_MS)
        socket.setsockopt(zmq.SNDTIMEO, _TIMEOUT_MS)
        socket.setsockopt(zmq.LINGER, 0)
        return visualizer

    def update(self, data: mujoco.MjData) -> bool:
        """Send the moving bodies' poses; False while the server does not answer.

        A busy server (several views open on a loaded machine) may miss the timeout once: the
        request socket is then replaced, so the view catches up instead of freezing for good.
        """
        if time.monotonic() < self._retry_at:
            return False
        window = self.visualizer.window
        try:
            for body in self._moving:
                window.send(
                    meshcat.commands.SetTransform(body_transform(data, body), self._paths[body])
                )
            for command in self.frames.update_commands(data):
                window.send(command)
        except zmq.ZMQError:
            self.failed = True
            self._misses += 1  # back off, so a server that is gone stalls the physics rarely
            self._retry_at = time.monotonic() + min(30.0, 0.5 * 2**self._misses)
            self.close()
            self.visualizer = self._connect()  # a REQ socket that timed out cannot send again
            return False
        self.failed, self._misses = False, 0
        self.updates += 1
        return True

    def close(self) -> None:
        """Close the connection to the server."""
        with contextlib.suppress(Exception):
            self.visualizer.window.zmq_socket.close(linger=0)
