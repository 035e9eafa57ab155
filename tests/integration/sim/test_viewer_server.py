"""The meshcat server: only the course's own origins reach its websocket; meshcat's protocol."""

from __future__ import annotations

import ast
import asyncio
import inspect
import subprocess
import sys
import textwrap
from collections.abc import Iterator

import numpy as np
import pytest
import tornado.httpclient
import tornado.websocket
from meshcat.commands import SetTransform
from meshcat.path import Path as MeshcatPath
from meshcat.servers.zmqserver import ZMQWebSocketBridge

from course_lib.testing import independent_env
from course_lib.viz.live import ServerWindow
from course_lib.viz.server import ORIGINS_ENV, LocalBridge, origin_allowed

HUB = "https://hub.example.org"


@pytest.fixture(scope="module")
def server() -> Iterator[tuple[str, int]]:
    """Run `python -m course_lib.viz.server` (one configured origin); yield (zmq url, port)."""
    env = independent_env(**{ORIGINS_ENV: HUB})
    process = subprocess.Popen(
        [sys.executable, "-m", "course_lib.viz.server"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        env=env,
    )
    try:
        assert process.stdout is not None
        zmq_url = process.stdout.readline().strip().split("=", 1)[1]
        web_url = process.stdout.readline().strip().split("=", 1)[1]
        yield zmq_url, int(web_url.rsplit(":", 1)[1].split("/")[0])
    finally:
        process.terminate()
        process.wait(timeout=10)
        if process.stdout is not None:
            process.stdout.close()


def _connect(port: int, headers: dict[str, str]) -> int:
    """Open the viewer's websocket with `headers`; return 101 when accepted, else the status."""

    async def attempt() -> int:
        request = tornado.httpclient.HTTPRequest(f"ws://127.0.0.1:{port}/", headers=headers)
        try:
            connection = await asyncio.wait_for(tornado.websocket.websocket_connect(request), 10)
        except tornado.httpclient.HTTPClientError as err:
            return err.code
        connection.close()
        return 101

    return asyncio.run(attempt())


def test_the_viewer_page_own_origin_is_accepted(server: tuple[str, int]) -> None:
    port = server[1]
    assert _connect(port, {"Origin": f"http://127.0.0.1:{port}"}) == 101


def test_jupyter_proxy_origin_is_accepted(server: tuple[str, int]) -> None:
    # jupyter-server-proxy forwards the browser's Host and Origin: both name the Jupyter server.
    headers = {"Origin": "http://127.0.0.1:8888", "Host": "127.0.0.1:8888"}
    assert _connect(server[1], headers) == 101


def test_configured_hub_origin_is_accepted(server: tuple[str, int]) -> None:
    assert _connect(server[1], {"Origin": HUB}) == 101


@pytest.mark.parametrize(
    "origin", ["http://evil.example", "http://127.0.0.1:1", "null", "https://hub.example.org.evil"]
)
def test_another_origin_is_refused(server: tuple[str, int], origin: str) -> None:
    assert _connect(server[1], {"Origin": origin}) == 403


def test_origin_rules() -> None:
    assert origin_allowed("http://LOCALHOST:8888", "localhost:8888")
    assert not origin_allowed("http://localhost:8889", "localhost:8888")
    assert origin_allowed("https://hub.example.org/", None, [HUB])
    assert not origin_allowed("http://hub.example.org", None, [HUB])  # another scheme
    assert not origin_allowed("http://x", None, ["", " "])


def test_server_window_speaks_meshcats_protocol(server: tuple[str, int]) -> None:
    """A transform sent through ServerWindow reaches a viewer that connects afterwards."""
    window = ServerWindow(server[0])
    try:
        window.send(SetTransform(np.eye(4), MeshcatPath(("meshcat", "probe"))))
    finally:
        window.close()

    async def first_message() -> bytes:
        connection = await tornado.websocket.websocket_connect(f"ws://127.0.0.1:{server[1]}/")
        message = await asyncio.wait_for(connection.read_message(), 10)
        connection.close()
        return message

    message = asyncio.run(first_message())
    assert b"set_transform" in message and b"/meshcat/probe" in message


def _attributes_set_by_init(cls: type) -> set[str]:
    tree = ast.parse(textwrap.dedent(inspect.getsource(cls.__init__)))
    names = set()
    for node in ast.walk(tree):
        store = isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store)
        if store and isinstance(node.value, ast.Name) and node.value.id == "self":
            names.add(node.attr)
    return names


def test_local_bridge_sets_what_meshcats_init_sets() -> None:
    """Tripwire: LocalBridge skips meshcat's __init__, so it must set every attribute it sets."""
    expected = _attributes_set_by_init(ZMQWebSocketBridge)
    assert {"tree", "websocket_pool", "zmq_socket", "web_url"} <= expected  # the parse works
    bridge = LocalBridge()
    try:
        missing = expected - set(vars(bridge))
    finally:
        bridge.zmq_stream.close()
    assert not missing, f"meshcat's bridge now also sets {sorted(missing)}: update LocalBridge"
