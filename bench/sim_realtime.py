"""The world at real time: CPU share of the simulation process, pose updates reaching the view."""

from __future__ import annotations

import asyncio
import os
import sys
import time

from course_lib.notebook import start_world
from course_lib.session.session import Session

WINDOW_S = 10.0
TICKS = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid: int) -> float:
    """Return user + system CPU seconds of process `pid`."""
    with open(f"/proc/{pid}/stat") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / TICKS


def cpu_share(pid: int, seconds: float) -> float:
    """Return the share of one core `pid` used over the next `seconds`."""
    before, start = cpu_seconds(pid), time.monotonic()
    time.sleep(seconds)
    return (cpu_seconds(pid) - before) / (time.monotonic() - start)


async def viewer_updates(port: int, seconds: float) -> float:
    """Count base_link transforms a websocket client (a browser's place) receives per second."""
    import tornado.websocket

    connection = await tornado.websocket.websocket_connect(f"ws://127.0.0.1:{port}/")
    skip_until = time.monotonic() + 0.5  # the scene itself arrives first
    while time.monotonic() < skip_until:
        await asyncio.wait_for(connection.read_message(), 2.0)
    count, start = 0, time.monotonic()
    while time.monotonic() - start < seconds:
        message = await asyncio.wait_for(connection.read_message(), 2.0)
        count += isinstance(message, bytes) and b"/meshcat/mujoco/base_link" in message
    connection.close()
    return count / seconds


def main() -> None:
    for show in (False, True):
        session = Session()
        try:
            world = start_world(session, show=show)
            world.drive(0.1, 0.3)
            time.sleep(2.0)  # past start-up
            share = cpu_share(world.process.pid, WINDOW_S)
            label = "3D view open, nobody watching" if show else "no 3D view"
            print(
                f"sim process CPU at real time, {label}: {100 * share:5.1f}% of one core "
                f"(goal < 25%; {WINDOW_S:g} s window)"
            )
            if show:  # the simulation process serves the view too (viz.server.serve_in_thread)
                rate = asyncio.run(viewer_updates(world.viewer.port, 5.0))
                print(
                    f"pose updates reaching a viewer client: {rate:5.1f} per second "
                    f"(goal >= {0.95 * world.settings.rates.viewer_hz:g})"
                )
                from sensor_msgs.msg import Image

                frames: list[float] = []
                session.node.create_subscription(
                    Image,
                    "/camera/image_raw",
                    lambda _m: frames.append(time.monotonic()),  # noqa: B023 - read right below
                    2,
                )
                time.sleep(2.0)  # the render thread's EGL start-up
                share = cpu_share(world.process.pid, WINDOW_S)
                print(
                    f"sim process CPU with a /camera/image_raw subscriber: {100 * share:5.1f}% "
                    f"({len([f for f in frames if f > frames[-1] - 5.0]) / 5.0:.1f} frames/s)"
                )
            print(f"simulated time after the run: {world.odom().time_s:.1f} s", file=sys.stderr)
        finally:
            session.close()


if __name__ == "__main__":
    main()
