"""The simulation process: `python -m course_lib.sim` runs the whole world as one process."""

from __future__ import annotations

import argparse
import contextlib
import signal
import sys
import time
from collections.abc import Sequence
from typing import TYPE_CHECKING

from ..core.errors import CourseError

if TYPE_CHECKING:  # the lab's service imports READY_TEXT: it never reads the settings (YAML)
    from ..config.simulation import SimulationSettings
    from ..viz.server import ThreadedServer

__all__ = ["READY_TEXT", "main", "parse_args"]

READY_TEXT = "MuJoCo world ready"


def parse_args(argv: Sequence[str]) -> argparse.Namespace:
    """Parse the simulation's own options (ROS arguments after --ros-args are left to rclpy)."""
    parser = argparse.ArgumentParser(
        prog="python -m course_lib.sim",
        description="Run the MuJoCo TurtleBot3 Waffle Pi world with its ROS 2 nodes.",
    )
    parser.add_argument("--config", help="simulation YAML (default: config/simulation.yaml)")
    parser.add_argument(
        "--real-time-factor",
        type=float,
        default=None,
        help="override the config: 1 = real time, 0 = as fast as possible",
    )
    parser.add_argument("--paused", action="store_true", help="start with the physics paused")
    parser.add_argument(
        "--serve-view",
        action="store_true",
        help="serve the 3D view from this process (prints zmq_url=... and web_url=...)",
    )
    parser.add_argument(
        "--duration",
        type=float,
        default=None,
        help="stop after this many simulated seconds (benchmarks)",
    )
    return parser.parse_args(argv)


def _settings(args: argparse.Namespace) -> SimulationSettings:
    from ..config.simulation import load_simulation_settings

    settings = load_simulation_settings(args.config)
    if args.real_time_factor is not None:
        import dataclasses

        settings = dataclasses.replace(settings, real_time_factor=args.real_time_factor)
    return settings


def main(argv: Sequence[str] | None = None) -> int:
    """Run until SIGINT/SIGTERM (or --duration); 0 on a clean stop, 2 on a settings error.

    1 when a ROS callback raised: its traceback is logged, then this last line names it.
    """
    import rclpy
    from rclpy.signals import SignalHandlerOptions
    from rclpy.utilities import remove_ros_args

    argv = list(sys.argv if argv is None else argv)
    args = parse_args(remove_ros_args(argv)[1:])
    try:
        settings = _settings(args)
    except CourseError as err:
        print(err, file=sys.stderr, flush=True)
        return 2
    from ..core.host.scheduling import as_background_work
    from .world import gl_backend

    gl_backend.defer("egl")  # headless offscreen camera, loaded with the camera's first frame
    from .ros.bridge import Bridge
    from .view.live import LiveView
    from .world.physics import Simulation

    server = _serve_view() if args.serve_view else None
    sim = Simulation(settings)
    context = rclpy.Context()
    rclpy.init(args=argv, context=context, signal_handler_options=SignalHandlerOptions.NO)
    viewer = None
    if server is not None:
        viewer = LiveView(server.zmq_url, sim.model, sim.data, local=server)
    bridge = Bridge(sim, context, viewer=viewer)
    bridge.paused = args.paused
    if args.paused:
        bridge.nodes["mujoco"].set_parameters([rclpy.parameter.Parameter("paused", value=True)])
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: bridge.stop())
    logger = bridge.nodes["mujoco"].get_logger()

    def ready() -> None:
        logger.info(
            f"{READY_TEXT}: real time factor {bridge.pacer.real_time_factor:g}, "
            f"timestep {sim.timestep:g} s, {len(bridge.nodes)} nodes"
        )

    started = [0.0, 0.0]

    def ready_and_mark() -> None:
        ready()
        started[:] = [sim.time, time.monotonic()]
        as_background_work()  # up: from now on the learners' kernels and nodes go first

    try:
        bridge.run(ready=ready_and_mark, max_sim_time_s=args.duration)
        if bridge.spin_error is not None:
            error = bridge.spin_error
            logger.error(f"the simulation's ROS thread stopped: {type(error).__name__}: {error}")
            return 1
        simulated, wall = sim.time - started[0], time.monotonic() - started[1]
        logger.info(
            f"Simulated {simulated:.2f} s in {wall:.2f} s of wall time "
            f"({simulated / max(wall, 1e-9):.1f}x real time)"
        )
    finally:
        # A terminal's Ctrl-C reaches the whole process group and `ros2 launch` forwards another
        # SIGINT: ignore late ones, or one landing during interpreter exit (when Python has put
        # the default action back) would kill us with -SIGINT after a clean stop.
        for signum in (signal.SIGINT, signal.SIGTERM):
            signal.signal(signum, signal.SIG_IGN)
        bridge.close()
        if viewer is not None:
            viewer.close()
        if server is not None:
            server.stop()
        with contextlib.suppress(Exception):
            context.try_shutdown()
    return 0


def _serve_view() -> ThreadedServer:
    """Serve the 3D view from a thread of this process; say where, as the viewer server does."""
    from ..viz.server import default_origins, serve_in_thread

    server = serve_in_thread(default_origins())
    print(f"zmq_url={server.zmq_url}", flush=True)
    print(f"web_url={server.web_url}", flush=True)
    return server
