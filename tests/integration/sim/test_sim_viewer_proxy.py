"""The 3D view through jupyter-server-proxy, as on JupyterHub: page, script and websocket."""

from __future__ import annotations

import asyncio
import socket
import sys
import time
import urllib.request

import pytest

from course_lib.config.simulation import load_simulation_settings
from course_lib.core.host.ports import free_port
from course_lib.notebook import start_world
from course_lib.session.session import Session

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

TOKEN = "course-test-token"


def _wait_listening(port: int, timeout: float = 30.0) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with socket.socket() as probe:
            if probe.connect_ex(("127.0.0.1", port)) == 0:
                return
        time.sleep(0.1)
    raise TimeoutError(f"nothing listens on {port}")


async def _transforms_through(url: str, seconds: float) -> int:
    import tornado.websocket

    connection = await tornado.websocket.websocket_connect(url)
    count, start = 0, time.monotonic()
    while time.monotonic() - start < seconds:
        message = await asyncio.wait_for(connection.read_message(), 2.0)
        count += isinstance(message, bytes) and b"set_transform" in message
    connection.close()
    while await asyncio.wait_for(connection.read_message(), 5.0) is not None:
        pass  # until the close handshake ends and tornado closes the socket
    return count


def test_view_works_through_jupyter_server_proxy() -> None:
    session = Session()
    try:
        world = start_world(session, show=True)
        world.drive(0.2)  # the view sends poses while the robot moves (and a browser watches)
        jupyter_port = free_port()
        session.spawn(
            [
                sys.executable,
                "-m",
                "jupyter",
                "server",
                "--no-browser",
                "--allow-root",
                "--ip=127.0.0.1",
                f"--port={jupyter_port}",
                f"--ServerApp.token={TOKEN}",
            ],
            name="jupyter",
        )
        _wait_listening(jupyter_port)
        base = f"http://127.0.0.1:{jupyter_port}{world.viewer.url}"
        assert world.viewer.url == f"/proxy/{world.viewer.port}/static/"
        page = urllib.request.urlopen(f"{base}?token={TOKEN}", timeout=10).read()
        assert b"viewer.connect(base" in page  # the page that finds its websocket behind a proxy
        script = urllib.request.urlopen(f"{base}main.min.js?token={TOKEN}", timeout=10).read()
        assert len(script) > 500_000
        socket_url = f"ws://127.0.0.1:{jupyter_port}/proxy/{world.viewer.port}/?token={TOKEN}"
        rate = load_simulation_settings().rates.viewer_hz
        assert asyncio.run(_transforms_through(socket_url, 1.0)) >= 0.8 * rate
    finally:
        session.close()
