"""A per-domain background process holding a warm client node, serving `ros2` commands.

Like the real `ros2 daemon`, it keeps discovery going between commands, so a terminal
`ros2 param get` costs one socket round trip instead of an rclpy start and a discovery wait.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import socket
import threading
import time
from collections.abc import Mapping
from typing import Any

from ..processes import ChildProcess, spawn
from .commands import Context, execute
from .connect import IDLE_ENV, daemon_argv, daemon_socket
from .console import StreamingConsole

__all__ = ["serve", "start_daemon"]


def start_daemon(env: Mapping[str, str]) -> ChildProcess:
    """Start the daemon for env's ROS_DOMAIN_ID as a child owned by this process."""
    if not env.get("ROS_DOMAIN_ID"):
        raise ValueError("start_daemon needs ROS_DOMAIN_ID in env (the course's domain)")
    return spawn(daemon_argv(), name=f"ros2-daemon-{env['ROS_DOMAIN_ID']}", env=env)


class _Connection:
    """One client connection: a command in, framed output back, cancel on hang-up."""

    def __init__(self, sock: socket.socket, client_factory: Any) -> None:
        self.sock = sock
        self.client_factory = client_factory
        self.lock = threading.Lock()

    def send(self, frame: dict[str, Any]) -> None:
        data = json.dumps(frame).encode() + b"\n"
        with self.lock:
            self.sock.sendall(data)

    def watch_hang_up(self, console: StreamingConsole) -> None:
        with contextlib.suppress(OSError):
            while self.sock.recv(1024):
                pass
        console.cancelled.set()

    def handle(self) -> None:
        with contextlib.suppress(OSError, ValueError), self.sock:
            line = self.sock.makefile("r", encoding="utf-8").readline()
            request = json.loads(line)

            def write(stream: str, text: str) -> None:
                try:
                    self.send({"o" if stream == "stdout" else "e": text})
                except OSError:
                    console.cancelled.set()

            console = StreamingConsole(write, width=int(request.get("width", 80)))
            threading.Thread(target=self.watch_hang_up, args=(console,), daemon=True).start()
            ctx = Context(console, self.client_factory, cwd=request.get("cwd"))
            code = execute(list(request["argv"]), ctx)
            self.send({"exit": code})


def _claim(path: str) -> socket.socket | None:
    """Bind the domain's socket unless a live daemon already answers there."""
    probe = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        probe.connect(path)
        return None  # someone serves this domain already
    except OSError:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(path)
    finally:
        probe.close()
    server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    server.bind(path)
    os.chmod(path, 0o600)
    server.listen(16)
    return server


def serve(*, idle_s: float | None = None) -> int:
    """Serve commands for this process's ROS_DOMAIN_ID until killed (or idle for idle_s)."""
    from ..session import get_session
    from .client import RosClient

    stopping = threading.Event()
    if threading.current_thread() is threading.main_thread():
        # Ctrl-C stops it cleanly, even when started in the background (SIGINT ignored there).
        signal.signal(signal.SIGINT, lambda *_: stopping.set())
    domain = os.environ.get("ROS_DOMAIN_ID", "")
    path = str(daemon_socket(domain))
    server = _claim(path)
    if server is None:
        return 0
    session = get_session(domain_id=int(domain)) if domain else get_session()
    client = RosClient(session.node, session.wait_future)
    server.settimeout(1.0)
    last = time.monotonic()
    try:
        while not stopping.is_set() and (idle_s is None or time.monotonic() - last < idle_s):
            try:
                conn, _ = server.accept()
            except TimeoutError:
                continue
            last = time.monotonic()
            handler = _Connection(conn, lambda: client)
            threading.Thread(target=handler.handle, daemon=True).start()
    finally:
        server.close()
        with contextlib.suppress(FileNotFoundError):
            os.unlink(path)
        session.close()
    return 0


if __name__ == "__main__":
    idle = os.environ.get(IDLE_ENV)
    raise SystemExit(serve(idle_s=float(idle) if idle else None))
