"""A kernel on a learner's hub server, started and driven through the hub's proxy.

Not a bench script itself. The kernel starts as the page starts one (`POST /api/kernels` on
`{hub}/user/{name}`) and its cells go over the kernel's websocket, so the hub's proxy carries
every message, as it does for a learner's browser. A bench._labs.CellKernel:
`submit(code)` then `collect(msg_id)`, `run(code)`, and `shutdown()`.
"""

from __future__ import annotations

import asyncio
import json
import queue
import threading
import time
import uuid
from datetime import datetime, timezone
from typing import Any

import requests

from bench._labs import CellKernel

__all__ = ["HubKernel"]


class HubKernel(CellKernel):
    """One kernel of `base` (a learner's server through the hub, `{hub}/user/{name}`)."""

    def __init__(self, base: str, token: str, timeout: float = 120.0) -> None:
        from tornado.httpclient import HTTPRequest
        from tornado.websocket import websocket_connect

        self.base, self.token = base, token
        self.headers = {"Authorization": f"token {token}"}
        reply = requests.post(f"{base}/api/kernels", json={}, headers=self.headers, timeout=60)
        reply.raise_for_status()
        self.id = str(reply.json()["id"])
        self.session = uuid.uuid4().hex
        self.messages: queue.Queue[dict[str, Any] | None] = queue.Queue()
        # The websocket is read all the time, on a loop of its own: a socket left unread
        # while a long cell runs would not answer the server's pings, and be closed.
        self.loop = asyncio.new_event_loop()
        threading.Thread(target=self.loop.run_forever, name="hub-kernel", daemon=True).start()
        url = f"{base.replace('http', 'ws', 1)}/api/kernels/{self.id}/channels"
        request = HTTPRequest(f"{url}?session_id={self.session}", headers=self.headers)

        async def connect() -> Any:
            ws = await websocket_connect(request)
            self.loop.create_task(self._pump(ws))
            return ws

        self.ws = asyncio.run_coroutine_threadsafe(connect(), self.loop).result(60)
        self._wait_ready(timeout)

    async def _pump(self, ws: Any) -> None:
        while (text := await ws.read_message()) is not None:
            self.messages.put(json.loads(text))
        self.messages.put(None)  # closed

    def _wait_ready(self, timeout: float) -> None:
        """Ask kernel_info until the kernel answers (it starts its course set-up first)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            msg_id = self._send("kernel_info_request", {}, "shell")
            try:
                while True:
                    message = self.read_message(min(2.0, max(0.1, deadline - time.monotonic())))
                    if message["parent_header"].get("msg_id") == msg_id and (
                        message["msg_type"] == "kernel_info_reply"
                    ):
                        return
            except TimeoutError:
                continue
        raise TimeoutError(f"the kernel did not answer within {timeout:g} s")

    def _send(self, msg_type: str, content: dict[str, Any], channel: str) -> str:
        msg_id = uuid.uuid4().hex
        header = {
            "msg_id": msg_id,
            "msg_type": msg_type,
            "session": self.session,
            "username": "bench",
            "version": "5.3",
            "date": datetime.now(timezone.utc).isoformat(),
        }
        message = {
            "header": header,
            "parent_header": {},
            "metadata": {},
            "content": content,
            "channel": channel,
            "buffers": [],
        }

        async def write() -> None:
            await self.ws.write_message(json.dumps(message))

        asyncio.run_coroutine_threadsafe(write(), self.loop).result(60)
        return msg_id

    def read_message(self, timeout: float) -> dict[str, Any]:
        try:
            message = self.messages.get(timeout=timeout)
        except queue.Empty as exc:
            raise TimeoutError from exc
        if message is None:
            raise RuntimeError("the kernel's websocket closed")
        return message

    def submit(self, code: str) -> str:
        """Start executing `code` as one cell; return its message id for collect()."""
        content = {
            "code": code,
            "silent": False,
            "store_history": False,
            "user_expressions": {},
            "allow_stdin": False,
            "stop_on_error": True,
        }
        return self._send("execute_request", content, "shell")

    def shutdown(self) -> None:
        """Close the websocket and stop the kernel (and every course process it owns)."""
        try:
            self.loop.call_soon_threadsafe(self.ws.close)
            self.loop.call_soon_threadsafe(self.loop.stop)
        finally:
            requests.delete(f"{self.base}/api/kernels/{self.id}", headers=self.headers, timeout=60)
