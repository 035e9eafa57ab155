"""The course's lab server bridges a page and its kernel safely: one websocket message with an
ill-sized legacy header cost a stock Jupyter server 3 GiB (77 -> 3,342 MiB here), which a
chaos walk met as a lab server at 3.4 GB; the course's bridge refuses it and stays usable, in
both wire protocols (course_lib/lab/kernel_socket.py)."""

from __future__ import annotations

import asyncio
import json
import uuid
from collections.abc import Iterator
from typing import Any

import psutil
import pytest
from jupyter_client.session import Session
from lab_server import ARTIFACTS, LabServer
from tornado.httpclient import AsyncHTTPClient, HTTPRequest
from tornado.websocket import websocket_connect

from course_lib.lab.kernel_socket import V1_PROTOCOL

pytestmark = [pytest.mark.slow]

# a message of the current protocol (v1) starts with its number of offsets, little-endian: read
# as a legacy header, 6 offsets ask jupyter_server for 100,663,296
V1_READ_AS_LEGACY = (6).to_bytes(8, "little") + bytes(56)
GROWTH_ALLOWED_MIB = 200


@pytest.fixture(scope="module")
def lab() -> Iterator[LabServer]:
    server = LabServer([], ARTIFACTS / "lab-kernel-socket")
    try:
        yield server
    finally:
        server.stop()


def _server(lab: LabServer) -> psutil.Process:
    root = psutil.Process(lab.process.pid)
    return next(p for p in root.children(recursive=True) if "jupyter" in " ".join(p.cmdline()[:2]))


def _kernel_info_request() -> dict[str, Any]:
    return Session(key=b"").msg("kernel_info_request")


def _v1_frame(channel: str, message: dict[str, Any]) -> bytes:
    """Return `message` as the v1 protocol frames it: the number of offsets, the offsets (each
    part's start, then the end), the channel, then the message's four parts."""
    parts = [channel.encode()] + [
        json.dumps(message[key], default=str).encode()
        for key in ("header", "parent_header", "metadata", "content")
    ]
    offsets = [8 * (len(parts) + 2)]
    for part in parts:
        offsets.append(offsets[-1] + len(part))
    numbers = [len(offsets), *offsets]
    return b"".join(n.to_bytes(8, "little") for n in numbers) + b"".join(parts)


def _v1_reply_type(frame: bytes) -> str:
    count = int.from_bytes(frame[:8], "little")
    offsets = [int.from_bytes(frame[8 + 8 * i : 16 + 8 * i], "little") for i in range(count)]
    header = frame[offsets[1] : offsets[2]]
    return str(json.loads(header)["msg_type"])


async def _talk(lab: LabServer, *, v1: bool) -> list[str]:
    """Open a kernel's websocket (legacy: send the ill-sized message first), then ask for
    kernel info; return the types of the replies."""
    auth = {"Authorization": f"token {lab.token}"}
    http = AsyncHTTPClient()
    made = await http.fetch(
        HTTPRequest(f"{lab.base_url}/api/kernels", method="POST", body="{}", headers=auth)
    )
    kernel = json.loads(made.body)["id"]
    url = f"ws://127.0.0.1:{lab.port}/api/kernels/{kernel}/channels?session_id={uuid.uuid4()}"
    socket = await websocket_connect(
        HTTPRequest(url, headers=auth), subprotocols=[V1_PROTOCOL] if v1 else None
    )
    try:
        assert socket.selected_subprotocol == (V1_PROTOCOL if v1 else None)
        if not v1:
            await socket.write_message(V1_READ_AS_LEGACY, binary=True)
        request = _kernel_info_request()
        if v1:
            await socket.write_message(_v1_frame("shell", request), binary=True)
        else:
            await socket.write_message(json.dumps({**request, "channel": "shell"}, default=str))
        replies: list[str] = []
        while "kernel_info_reply" not in replies:
            frame = await asyncio.wait_for(socket.read_message(), timeout=30)
            if frame is None:  # the server closed the socket (a stock server, on that message)
                replies.append("closed")
                break
            if isinstance(frame, bytes):
                replies.append(_v1_reply_type(frame))
            else:
                replies.append(json.loads(frame)["header"]["msg_type"])
        return replies
    finally:
        socket.close()
        await http.fetch(
            HTTPRequest(f"{lab.base_url}/api/kernels/{kernel}", method="DELETE", headers=auth)
        )


def test_an_ill_sized_legacy_header_costs_the_server_nothing(lab: LabServer) -> None:
    server = _server(lab)
    before = server.memory_info().rss >> 20
    replies = asyncio.run(_talk(lab, v1=False))
    after = server.memory_info().rss >> 20
    assert after - before < GROWTH_ALLOWED_MIB, f"the server grew from {before} to {after} MiB"
    assert "kernel_info_reply" in replies, f"the socket is no longer usable: {replies}"


def test_the_current_protocol_still_bridges(lab: LabServer) -> None:
    assert "kernel_info_reply" in asyncio.run(_talk(lab, v1=True))
