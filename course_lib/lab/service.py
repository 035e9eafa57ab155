"""The lab's machine service: a Unix socket next to JupyterLab that owns the shared world.

`make lab` starts it (`MachineService.start`) before JupyterLab and stops it after; kernels
and terminals find it through the `COURSE_LAB_SOCKET` environment variable.
"""

from __future__ import annotations

import contextlib
import logging
import socket
import socketserver
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..core.errors import CourseError
from ..sim.launcher import Spawner
from .daemon_keeper import DaemonKeeper
from .protocol import MAX_LINE, decode, encode, failure
from .register import NodeRecord, NodeRegister
from .world_keeper import WorldKeeper

__all__ = ["MachineService"]

_log = logging.getLogger(__name__)


class _Handler(socketserver.StreamRequestHandler):
    def handle(self) -> None:
        assert isinstance(self.server, _Server)  # the only server this handler serves
        service = self.server.machine
        line = self.rfile.readline(MAX_LINE)
        if not line:
            return
        try:
            request = decode(line)
            answer = service.answer(request)
        except CourseError as exc:
            answer = failure(exc.message, exc.hint or "")
        except Exception as exc:  # a bad request must never stop the service
            _log.exception("machine service request failed")
            answer = failure(f"The lab's machine service failed: {exc}", "see the lab terminal.")
        with contextlib.suppress(OSError):
            self.wfile.write(encode(answer))


class _Server(socketserver.ThreadingMixIn, socketserver.UnixStreamServer):
    daemon_threads = True
    machine: MachineService


class MachineService:
    """Answer the kernels' and terminals' requests: the world, the register of lessons'
    nodes, and the lab's ros2 daemon (started with the first terminal)."""

    def __init__(self, path: Path, spawn: Spawner, daemon: DaemonKeeper | None = None) -> None:
        self.path = path
        self.world = WorldKeeper(spawn)
        self.nodes = NodeRegister()
        self.daemon = daemon
        self._ops: dict[str, Callable[[dict[str, Any]], dict[str, Any]]] = {
            "ping": lambda _r: {},
            "world.ensure": lambda r: self.world.ensure(
                r.get("config"), float(r.get("timeout", 30))
            ),
            "world.status": lambda _r: self.world.status(),
            "world.stop": self._stop_world,
            "node.take": self._take,
            "node.stop": lambda r: {"stopped": bool(self.nodes.stop(str(r["tag"])))},
            "node.register": self._register,
            "node.list": lambda _r: {"nodes": [rec.as_dict() for rec in self.nodes.records()]},
            "daemon.ensure": self._ensure_daemon,
        }
        self._server: _Server | None = None
        self._thread: threading.Thread | None = None
        self._stopping = False  # stop() sets it, then wakes the serving loop

    def answer(self, request: dict[str, Any]) -> dict[str, Any]:
        """Return the answer to one request."""
        op = request.get("op")
        handler = self._ops.get(str(op))
        if handler is None:
            return failure(f"unknown request {op!r}", f"known: {', '.join(sorted(self._ops))}")
        return {"ok": True, **handler(request)}

    def _stop_world(self, _request: dict[str, Any]) -> dict[str, Any]:
        self.world.stop()
        return {}

    def _ensure_daemon(self, _request: dict[str, Any]) -> dict[str, Any]:
        if self.daemon is None:
            raise CourseError("This lab keeps no ros2 daemon.", hint="run a `ros2` command.")
        return dict(self.daemon.ensure())

    def _take(self, request: dict[str, Any]) -> dict[str, Any]:
        record = self.nodes.take(str(request["executable"]))
        return {"stopped": record.as_dict() if record else None}

    def _register(self, request: dict[str, Any]) -> dict[str, Any]:
        fields = ("executable", "node", "tag", "label")
        self.nodes.register(NodeRecord(**{k: str(request[k]) for k in fields}))
        return {}

    def start(self) -> MachineService:
        """Listen on the socket in a background thread."""
        self.path.unlink(missing_ok=True)
        server = _Server(str(self.path), _Handler)
        server.machine = self
        self.path.chmod(0o600)
        self._server = server
        self._stopping = False
        self._thread = threading.Thread(
            target=self._serve, args=(server,), name="course-machine", daemon=True
        )
        self._thread.start()
        return self

    def _serve(self, server: _Server) -> None:
        """Answer each connection as it comes and sleep in between (serve_forever woke
        twice a second to look for a shutdown: most of an idle lab service's CPU)."""
        while not self._stopping:
            server.handle_request()

    def stop(self) -> None:
        """Stop listening, then stop the world; idempotent."""
        if self._server is not None:
            self._stopping = True
            with contextlib.suppress(OSError), socket.socket(socket.AF_UNIX) as wake:
                wake.connect(str(self.path))  # the loop's wait ends; it sees _stopping
            if self._thread is not None:
                self._thread.join(timeout=5.0)
            self._server.server_close()
            self._server = None
        self.path.unlink(missing_ok=True)
        self.world.stop()
        if self.daemon is not None:
            self.daemon.stop()
