"""The meshcat server as a child of the course session: 127.0.0.1, free ports, no leak.

Run as `python -m course_lib.viz.server`; it prints `zmq_url=...` and `web_url=...` once it
listens, then serves until it is stopped (the session stops it, or it dies with the kernel).
meshcat-python's own `Visualizer()` would start a server that outlives a killed kernel.
The simulation serves its own view in a thread (`serve_in_thread`, `python -m course_lib.sim
--serve-view`): one process less per world, and the same two lines.

Its command socket (meshcat's ZMQ, which takes any scene command, a JavaScript callback for
the learner's browser included) is a Unix socket in the user's private runtime folder
(`ipc://`), never a TCP port: no other account on the host can connect to it.

The viewer's websocket accepts a browser page only from the origin it serves: the viewer page
itself, or the Jupyter server (or hub) whose proxy forwards it, which keeps the request's Host.
Other origins (any other web page open in the learner's browser) are refused, unless listed
in COURSE_VIEWER_ORIGINS (comma-separated, e.g. `https://hub.example.org`) or `--origin`.

Besides meshcat's commands, the command socket takes two of the course's own, so a live view
costs nothing while no browser watches it: `set_transforms` (one frame's poses in one message,
forwarded to the browsers as one websocket message, kept for a browser that connects later)
and `watchers` (no data); both answer with the number of browsers connected that someone can
see, in ASCII digits (a page whose notebook tab is in the background says `hidden` on its
websocket and gets no poses until it says `shown`).

A simulation that serves its own view hands each frame to the server's thread directly
(`ThreadedServer.offer_poses`, no socket and no reply to wait for) and reads the count of
watchers from `ThreadedServer.watchers`.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import signal
import sys
import threading
from collections.abc import Iterable
from pathlib import Path
from typing import cast
from urllib.parse import urlsplit

import tornado.httpserver
import tornado.ioloop
import tornado.netutil
import tornado.web
from meshcat.servers.tree import SceneTree
from meshcat.servers.zmqserver import (
    VIEWER_HTML,
    VIEWER_ROOT,
    StaticFileHandlerNoCache,
    WebSocketHandler,
    ZMQWebSocketBridge,
)
from tornado.platform.asyncio import BaseAsyncIOLoop

from .command_sockets import command_socket_url
from .viewer_page import ViewerPage

__all__ = [
    "ORIGINS_ENV",
    "POSES_COMMAND",
    "WATCHERS_COMMAND",
    "LocalBridge",
    "ThreadedServer",
    "default_origins",
    "main",
    "origin_allowed",
    "serve_in_thread",
]

ORIGINS_ENV = "COURSE_VIEWER_ORIGINS"
POSES_COMMAND = b"set_transforms"
WATCHERS_COMMAND = b"watchers"


def _normal(origin: str) -> str:
    parts = urlsplit(origin.strip().lower())
    return f"{parts.scheme}://{parts.netloc}"


def origin_allowed(origin: str, host: str | None, allowed: Iterable[str] = ()) -> bool:
    """Return True for a page on the request's own host, or one of the `allowed` origins."""
    if host and urlsplit(origin.strip().lower()).netloc == host.strip().lower():
        return True
    return _normal(origin) in {_normal(a) for a in allowed if a.strip()}


class _SameOriginWebSocket(WebSocketHandler):
    """meshcat's websocket, for pages of the origins the course serves only.

    The page says `hidden` when nobody can see it (it draws no frames) and `shown` again: a
    hidden page gets no poses, and is no watcher.
    """

    hidden = False

    def check_origin(self, origin: str) -> bool:
        return origin_allowed(origin, self.request.headers.get("Host"), self.bridge.origins)

    def on_message(self, message: str | bytes) -> None:
        if message in ("hidden", b"hidden"):
            self.hidden = True
        elif message in ("shown", b"shown"):
            if self.hidden and self.bridge.latest_poses is not None:
                self.write_message(self.bridge.latest_poses, binary=True)
            self.hidden = False
        else:
            super().on_message(message)
            return
        self.bridge.count_watchers()

    def on_close(self) -> None:
        super().on_close()
        self.bridge.count_watchers()


class LocalBridge(ZMQWebSocketBridge):
    """meshcat's bridge bound to one host, on ports the operating system picks.

    meshcat's own __init__ listens on every interface and on fixed ports, so it is not called:
    this sets the same attributes itself (tests/integration/viz/test_viewer_server.py fails the day
    meshcat's __init__ sets one more).
    """

    def __init__(
        self, host: str = "127.0.0.1", port: int = 0, origins: Iterable[str] = ()
    ) -> None:
        self.host = host
        self.origins = tuple(origins)
        self.websocket_pool: set[WebSocketHandler] = set()
        self.app = tornado.web.Application(
            [
                (r"/static/(index\.html)?", ViewerPage),
                (
                    r"/static/(.*)",
                    StaticFileHandlerNoCache,
                    {"path": VIEWER_ROOT, "default_filename": VIEWER_HTML},
                ),
                (r"/", _SameOriginWebSocket, {"bridge": self}),
            ]
        )
        self.ioloop = tornado.ioloop.IOLoop.current()
        self.zmq_url = command_socket_url()
        self.zmq_socket, self.zmq_stream, _ = self.setup_zmq(self.zmq_url)
        sockets = tornado.netutil.bind_sockets(port, address=host)
        server = tornado.httpserver.HTTPServer(self.app)
        server.add_sockets(sockets)
        self.fileserver_port = sockets[0].getsockname()[1]
        self.web_url = f"http://{host}:{self.fileserver_port}/static/"
        self.tree = SceneTree()
        self.latest_poses: bytes | None = None
        self.watchers = 0  # pages someone can see; written by the server's thread only

    def remove_command_socket(self) -> None:
        """Remove the command socket's file once the server has stopped."""
        Path(self.zmq_url.removeprefix("ipc://")).unlink(missing_ok=True)

    def handle_zmq(self, frames: list[bytes]) -> None:
        """Serve the course's two commands (module docstring), meshcat's own otherwise."""
        command = frames[0]
        if command == POSES_COMMAND and len(frames) == 3:
            self.forward_poses(frames[2])
        elif command != WATCHERS_COMMAND:
            if command == b"delete":
                self.latest_poses = None  # a scene drawn again starts from its own poses
            super().handle_zmq(frames)
            return
        self.zmq_socket.send(str(self.watchers).encode())

    def forward_poses(self, message: bytes) -> None:
        """Send one frame's poses to the pages someone sees; keep them for later pages."""
        self.latest_poses = message
        for websocket in self._seen():
            websocket.write_message(message, binary=True)

    def count_watchers(self) -> None:
        """Count again the pages someone can see (after one connected, left, hid, showed)."""
        self.watchers = len(self._seen())

    def _seen(self) -> list[WebSocketHandler]:
        """Return the connected pages that someone can see (see _SameOriginWebSocket)."""
        return [w for w in self.websocket_pool if not getattr(w, "hidden", False)]

    def send_scene(self, websocket: WebSocketHandler) -> None:
        """Send the scene to a browser that just connected, then the latest poses."""
        super().send_scene(websocket)
        if self.latest_poses is not None:
            websocket.write_message(self.latest_poses, binary=True)
        self.count_watchers()


def default_origins() -> list[str]:
    """Return the other origins whose pages may connect, from COURSE_VIEWER_ORIGINS."""
    return [o for o in os.environ.get(ORIGINS_ENV, "").split(",") if o.strip()]


class ThreadedServer:
    """A LocalBridge serving from a thread of this process, with its own event loop."""

    def __init__(self, bridge: LocalBridge, thread: threading.Thread) -> None:
        self.bridge = bridge
        self.thread = thread
        self.zmq_url = bridge.zmq_url
        self.web_url = bridge.web_url
        self._lock = threading.Lock()
        self._pending: bytes | None = None  # the latest frame the server's thread has not sent

    @property
    def watchers(self) -> int:
        """Return how many pages someone can see are connected (0 once the server stopped)."""
        return self.bridge.watchers if self.thread.is_alive() else 0

    def offer_poses(self, message: bytes) -> bool:
        """From any thread: have the server forward one frame's poses (a `set_transforms`
        message); False if it no longer serves. Nothing waits for the server's thread.

        A frame replaces one the server's thread has not sent yet: a server that falls behind
        sends the latest poses once, not a burst of stale ones, and nothing piles up.
        """
        if not self.thread.is_alive():
            return False
        with self._lock:
            queued = self._pending is not None
            self._pending = message
        if not queued:
            self.bridge.ioloop.add_callback(self._forward_pending)
        return True

    @property
    def sending(self) -> bool:
        """Return True while an offered frame waits for the server's thread."""
        return self._pending is not None

    def _forward_pending(self) -> None:
        """On the server's thread: send the frame offered last (one call per frame offered
        while none was pending, so there is always one)."""
        with self._lock:
            message, self._pending = self._pending, None
        # never None: one call per frame offered while none was pending
        self.bridge.forward_poses(cast(bytes, message))

    def stop(self, timeout: float = 5.0) -> None:
        """Stop serving and remove the command socket's file; idempotent."""
        if self.thread.is_alive():
            self.bridge.ioloop.add_callback(self.bridge.ioloop.stop)
            self.thread.join(timeout)
        self.bridge.remove_command_socket()


def serve_in_thread(origins: Iterable[str] = (), timeout: float = 10.0) -> ThreadedServer:
    """Start a LocalBridge on 127.0.0.1 in a daemon thread; return once it listens."""
    made: list[LocalBridge | BaseException] = []
    listening = threading.Event()

    def serve() -> None:
        asyncio.set_event_loop(asyncio.new_event_loop())
        try:
            made.append(LocalBridge(origins=origins))
        except BaseException as error:  # reported to the starting thread, raised there
            made.append(error)
            return
        finally:
            listening.set()
        bridge = made[0]
        assert isinstance(bridge, LocalBridge)
        bridge.run()
        bridge.ioloop.close(all_fds=True)

    thread = threading.Thread(target=serve, name="meshcat-server", daemon=True)
    thread.start()
    if not listening.wait(timeout):
        raise TimeoutError(f"the 3D view's server did not listen within {timeout:g} s")
    if isinstance(made[0], BaseException):
        raise made[0]
    return ThreadedServer(made[0], thread)


def main(argv: list[str] | None = None) -> int:
    """Serve until SIGINT or SIGTERM."""
    parser = argparse.ArgumentParser(description="meshcat server for the course (127.0.0.1)")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=0, help="web port (0: a free one)")
    parser.add_argument(
        "--origin",
        action="append",
        default=default_origins(),
        help=f"another origin whose pages may connect (repeatable; also ${ORIGINS_ENV})",
    )
    args = parser.parse_args(argv)
    bridge = LocalBridge(args.host, args.port, origins=args.origin)
    print(f"zmq_url={bridge.zmq_url}", flush=True)
    print(f"web_url={bridge.web_url}", flush=True)

    # asyncio's own handlers wake the loop even when a zmq thread receives the signal; a plain
    # signal.signal() handler would wait for an event that never comes.
    # tornado's IOLoop.current() is an asyncio one (tornado >= 5 runs on asyncio)
    loop = cast(BaseAsyncIOLoop, bridge.ioloop).asyncio_loop
    for signum in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(signum, bridge.ioloop.stop)
    try:
        bridge.run()
    finally:
        bridge.remove_command_socket()
    return 0


if __name__ == "__main__":
    sys.exit(main())
