"""Stream the simulation's body poses to a running meshcat server (used by the sim process)."""

from __future__ import annotations

import contextlib
import io

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
        with contextlib.redirect_stdout(io.StringIO()):  # meshcat prints in its constructor
            self.visualizer = meshcat.Visualizer(zmq_url=zmq_url)
        socket = self.visualizer.window.zmq_socket
        socket.setsockopt(zmq.RCVTIMEO, _TIMEOUT_MS)
        socket.setsockopt(zmq.SNDTIMEO, _TIMEOUT_MS)
        socket.setsockopt(zmq.LINGER, 0)
        self._paths = body_paths(model)
        self._moving = moving_bodies(model)
        self.updates = 0
        self.failed = False
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

    def update(self, data: mujoco.MjData) -> bool:
        """Send the moving bodies' poses; False (and stop trying) once the server is gone."""
        if self.failed:
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
            return False
        self.updates += 1
        return True

    def close(self) -> None:
        """Close the connection to the server."""
        with contextlib.suppress(Exception):
            self.visualizer.window.zmq_socket.close(linger=0)
