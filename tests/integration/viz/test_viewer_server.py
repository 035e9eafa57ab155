"""The meshcat server: only the course's own origins reach its websocket; meshcat's protocol."""

from __future__ import annotations

import ast
import base64
import inspect
import os
import socket
import subprocess
import sys
import textwrap
from collections.abc import Iterator

import numpy as np
import pytest
from meshcat.commands import SetTransform
from meshcat.path import Path as MeshcatPath
from meshcat.servers.zmqserver import ZMQWebSocketBridge
from suite_env import independent_env

from course_lib.processes.domain import lease_domain
from course_lib.sim.view.live import ServerWindow
from course_lib.viz.server import ORIGINS_ENV, LocalBridge, origin_allowed

HUB = "https://hub.example.org"
_EARLY: dict[int, bytes] = {}  # bytes read past a handshake's headers, by socket


def _serve(argv: list[str], **extra: str) -> Iterator[tuple[str, int]]:
    """Run a process that serves the view; yield (zmq url, web port) from its first lines."""
    env = independent_env(**{ORIGINS_ENV: HUB}, **extra)
    process = subprocess.Popen(
        [sys.executable, *argv],
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


@pytest.fixture(scope="module")
def server() -> Iterator[tuple[str, int]]:
    """Run `python -m course_lib.viz.server` (one configured origin); yield (zmq url, port)."""
    yield from _serve(["-m", "course_lib.viz.server"])


@pytest.fixture(scope="module", params=["server alone", "in the simulation"])
def any_server(request: pytest.FixtureRequest) -> Iterator[tuple[str, int]]:
    """The view served either way: alone, or by the simulation (the lab's world)."""
    if request.param == "server alone":
        yield from _serve(["-m", "course_lib.viz.server"])
        return
    lease = lease_domain({})
    try:
        yield from _serve(
            ["-m", "course_lib.sim", "--serve-view"], ROS_DOMAIN_ID=str(lease.domain_id)
        )
    finally:
        lease.release()


def _handshake(port: int, headers: dict[str, str]) -> tuple[int, socket.socket]:
    """Open the viewer's websocket with `headers`; return the HTTP status and the socket.

    The server may send its first frame in the same packet as its reply's headers: what came
    after the headers is kept in `_EARLY` for `_first_frame`.
    """
    sock = socket.create_connection(("127.0.0.1", port), timeout=10)
    fields = {
        "Host": f"127.0.0.1:{port}",
        "Upgrade": "websocket",
        "Connection": "Upgrade",
        "Sec-WebSocket-Key": base64.b64encode(os.urandom(16)).decode(),
        "Sec-WebSocket-Version": "13",
        **headers,
    }
    request = "GET / HTTP/1.1\r\n" + "".join(f"{k}: {v}\r\n" for k, v in fields.items())
    sock.sendall((request + "\r\n").encode())
    reply = b""
    while b"\r\n\r\n" not in reply:
        chunk = sock.recv(4096)
        if not chunk:
            break
        reply += chunk
    _EARLY[sock.fileno()] = reply.partition(b"\r\n\r\n")[2]
    return int(reply.split(b" ", 2)[1]), sock


def _connect(port: int, headers: dict[str, str]) -> int:
    """Return 101 when the websocket is accepted, else the HTTP status (403: refused)."""
    status, sock = _handshake(port, headers)
    sock.close()
    return status


def _first_frame(sock: socket.socket) -> bytes:
    """Read one (unmasked, server-to-client) websocket frame's payload."""
    buffer = _EARLY.pop(sock.fileno(), b"")

    def read(count: int) -> bytes:
        nonlocal buffer
        while len(buffer) < count:
            chunk = sock.recv(65536)
            if not chunk:
                break
            buffer += chunk
        taken, buffer = buffer[:count], buffer[count:]
        return taken

    header = read(2)
    length = header[1] & 0x7F
    if length >= 126:
        length = int.from_bytes(read(2 if length == 126 else 8), "big")
    return read(length)


def test_the_viewer_page_own_origin_is_accepted(any_server: tuple[str, int]) -> None:
    port = any_server[1]
    assert _connect(port, {"Origin": f"http://127.0.0.1:{port}"}) == 101


def test_jupyter_proxy_origin_is_accepted(any_server: tuple[str, int]) -> None:
    # jupyter-server-proxy forwards the browser's Host and Origin: both name the Jupyter server.
    headers = {"Origin": "http://127.0.0.1:8888", "Host": "127.0.0.1:8888"}
    assert _connect(any_server[1], headers) == 101


def test_configured_hub_origin_is_accepted(any_server: tuple[str, int]) -> None:
    assert _connect(any_server[1], {"Origin": HUB}) == 101


@pytest.mark.parametrize(
    "origin", ["http://evil.example", "http://127.0.0.1:1", "null", "https://hub.example.org.evil"]
)
def test_another_origin_is_refused(any_server: tuple[str, int], origin: str) -> None:
    assert _connect(any_server[1], {"Origin": origin}) == 403


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

    status, sock = _handshake(server[1], {})
    with sock:
        assert status == 101
        message = _first_frame(sock)
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


def _url_reply(zmq_url: str) -> bytes | None:
    """Ask the command socket meshcat's `url` question; return the answer, None if none came."""
    import zmq

    context = zmq.Context()
    try:
        sock = context.socket(zmq.REQ)
        sock.setsockopt(zmq.LINGER, 0)
        sock.setsockopt(zmq.RCVTIMEO, 2000)
        sock.setsockopt(zmq.SNDTIMEO, 2000)
        sock.connect(zmq_url)
        sock.send(b"url")
        return sock.recv()
    except zmq.ZMQError:
        return None
    finally:
        context.destroy(linger=0)


@pytest.mark.skipif(os.geteuid() != 0, reason="acting as another account needs root")
def test_another_account_cannot_reach_the_command_socket(server: tuple[str, int]) -> None:
    """meshcat's command socket takes any scene command, a JavaScript callback included: it
    must answer its own user only (a TCP port on 127.0.0.1 answered every account)."""
    zmq_url, _port = server
    assert _url_reply(zmq_url) is not None, "the owner's own question went unanswered"
    child = os.fork()
    if child == 0:  # another account: nobody
        code = 3
        try:
            os.setgroups([])
            os.setgid(65534)
            os.setuid(65534)
            code = 0 if _url_reply(zmq_url) is None else 1
        finally:
            os._exit(code)
    _, status = os.waitpid(child, 0)
    assert os.waitstatus_to_exitcode(status) == 0, f"another account reached {zmq_url}"
