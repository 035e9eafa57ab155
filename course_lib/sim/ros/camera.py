"""The Raspberry Pi camera: MuJoCo renders offscreen (EGL) in its own thread, on demand.

A frame costs about 4 ms at 320x240 with shadows and reflections off (llvmpipe, no GPU), and
nothing at all while no one subscribes to /camera/image_raw or /camera/camera_info.
"""

from __future__ import annotations

import math
import threading
from typing import Any

import mujoco
import numpy as np
from sensor_msgs.msg import CameraInfo, Image

from ...config.simulation import Camera
from ..world import gl_backend
from .messages import to_stamp

__all__ = ["CAMERA_NAME", "CameraStream", "camera_info"]

CAMERA_NAME = "camera"
_OFF = (
    mujoco.mjtRndFlag.mjRND_SHADOW,
    mujoco.mjtRndFlag.mjRND_REFLECTION,
    mujoco.mjtRndFlag.mjRND_SKYBOX,
)


def camera_info(fovy_deg: float, width: int, height: int, frame_id: str) -> CameraInfo:
    """Return the pinhole CameraInfo of a MuJoCo camera (square pixels, no distortion)."""
    focal = (height / 2.0) / math.tan(math.radians(fovy_deg) / 2.0)
    cx, cy = width / 2.0, height / 2.0
    info = CameraInfo(width=width, height=height, distortion_model="plumb_bob")
    info.header.frame_id = frame_id
    info.d = [0.0] * 5
    info.k = [focal, 0.0, cx, 0.0, focal, cy, 0.0, 0.0, 1.0]
    info.r = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    info.p = [focal, 0.0, cx, 0.0, 0.0, focal, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
    return info


class CameraStream:
    """Render frames the physics loop asks for, in a thread that owns the GL context."""

    def __init__(
        self,
        model: mujoco.MjModel,
        settings: Camera,
        publishers: tuple[Any, Any],
        logger: Any,
        frame_id: str = "camera_rgb_optical_frame",
    ) -> None:
        self.model = _render_copy(model)
        self.data = mujoco.MjData(self.model)
        self.settings = settings
        self.image_pub, self.info_pub = publishers
        self.logger = logger
        self.frame_id = frame_id
        fovy = float(self.model.cam_fovy[self.model.camera(CAMERA_NAME).id])
        self.info = camera_info(fovy, settings.width_px, settings.height_px, frame_id)
        self.frames = 0
        self.failed = False
        self._request: tuple[float, np.ndarray] | None = None
        self._cond = threading.Condition()
        self._stop = False
        self._thread = threading.Thread(target=self._run, name="sim-camera", daemon=True)
        self._thread.start()

    @property
    def wanted(self) -> bool:
        """Return True if someone listens to the camera topics."""
        count = self.image_pub.get_subscription_count() + self.info_pub.get_subscription_count()
        return count > 0 and not self.failed

    def offer(self, sim_time: float, qpos: np.ndarray) -> None:
        """Ask for a frame of the state `qpos` at `sim_time` (drops an older unrendered one)."""
        with self._cond:
            self._request = (sim_time, qpos.copy())
            self._cond.notify()

    def _run(self) -> None:
        renderer = None
        try:
            while True:
                with self._cond:
                    while self._request is None and not self._stop:
                        self._cond.wait()
                    if self._stop:
                        return
                    sim_time, qpos = self._request  # type: ignore[misc]
                    self._request = None
                if renderer is None:  # the first subscriber pays EGL's start-up (about 2 s)
                    size = (self.settings.height_px, self.settings.width_px)
                    renderer = gl_backend.renderer(self.model, *size)
                self._publish(renderer, sim_time, qpos)
        except Exception as err:  # no EGL here: say so once, keep the world running
            self.failed = True
            self.logger.warning(f"camera disabled: offscreen rendering failed ({err})")
        finally:
            if renderer is not None:
                renderer.close()

    def _publish(self, renderer: mujoco.Renderer, sim_time: float, qpos: np.ndarray) -> None:
        self.data.qpos[:] = qpos
        mujoco.mj_fwdPosition(self.model, self.data)
        renderer.update_scene(self.data, camera=CAMERA_NAME)
        for flag in _OFF:
            renderer.scene.flags[flag] = False
        pixels = renderer.render()
        stamp = to_stamp(sim_time)
        image = Image(
            height=pixels.shape[0],
            width=pixels.shape[1],
            encoding="rgb8",
            is_bigendian=0,
            step=pixels.shape[1] * 3,
        )
        image.header.stamp = stamp
        image.header.frame_id = self.frame_id
        image.data = pixels.tobytes()
        self.info.header.stamp = stamp
        self.image_pub.publish(image)
        self.info_pub.publish(self.info)
        self.frames += 1

    def close(self) -> None:
        """End the render thread."""
        with self._cond:
            self._stop = True
            self._cond.notify()
        self._thread.join(timeout=2.0)


def _render_copy(model: mujoco.MjModel) -> mujoco.MjModel:
    """Return a copy of `model` set up for cheap offscreen frames (no MSAA, no shadow map)."""
    import copy

    clone = copy.copy(model)
    clone.vis.quality.shadowsize = 0
    clone.vis.quality.offsamples = 0
    clone.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_SENSOR)
    return clone
