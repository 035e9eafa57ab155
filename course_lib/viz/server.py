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

from ..core import procfs
from ..core.paths import runtime_dir
from ..core.ports import unix_socket_answers
from .page_access import PANEL_JS, ROBOT_STATE_JS, TOOLBAR_JS

__all__ = [
    "ORIGINS_ENV",
    "POSES_COMMAND",
    "WATCHERS_COMMAND",
    "LocalBridge",
    "ThreadedServer",
    "command_socket_url",
    "default_origins",
    "main",
    "origin_allowed",
    "remove_dead_command_sockets",
    "serve_in_thread",
]

ORIGINS_ENV = "COURSE_VIEWER_ORIGINS"
POSES_COMMAND = b"set_transforms"
WATCHERS_COMMAND = b"watchers"


# The toolbar (TF frames, Controls) is one Tab stop; the line under it says where the robot is
# (page_access). White on at least 70 % black: AA contrast over any part of the scene.
_PAGE = (
    """<!DOCTYPE html>
<html lang="en"><head><meta charset=utf-8><title>3D view of the simulated robot</title>
<style>body {margin: 0} #meshcat-pane {width: 100vw; height: 100vh; overflow: hidden}
#view-tools {position: absolute; left: 8px; top: 8px; display: flex; gap: 6px;
  align-items: center}
#view-tools > *, #robot-state {padding: 2px 6px; border: 0; border-radius: 4px;
  font: 13px sans-serif; color: #fff; background: rgba(0, 0, 0, 0.7); user-select: none}
#robot-state {position: absolute; left: 8px; bottom: 8px; margin: 0}</style>
</head><body><div id="meshcat-pane"></div>
<div id="view-tools" role="toolbar" aria-label="3D view">
<label id="tf-toggle" title="the frames /tf and /tf_static describe (x red, y green, z blue)">
<input type="checkbox" id="tf-frames"> TF frames</label>
<button type="button" id="view-controls" aria-expanded="false">Controls</button></div>
<p id="robot-state" role="status" aria-live="polite" aria-atomic="true">Robot: waiting for
the simulation</p>
<script src="main.min.js"></script>
<script>
// Drawn on demand: meshcat's own loop (off here) asks the browser for a frame 60 times a
// second for as long as the page is open, with nothing new to draw; in a browser without a
// GPU that kept a still robot's view at about a tenth of a core. Here a frame is asked for
// when meshcat marks the scene changed (a pose, the camera moved, a resize), and each
// frame of a playing animation asks for the next.
var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"), false);
(function () {
  var asked = false;
  function frame() {
    asked = false;
    viewer.animator.update();  // a playing animation marks the scene changed: next frame
    if (viewer.needs_render) { viewer.render(); }
  }
  function ask() {
    if (!asked) { asked = true; requestAnimationFrame(frame); }
  }
  var mark = viewer.set_dirty.bind(viewer);
  viewer.set_dirty = function () { mark(); ask(); };
  viewer.animate = ask;  // what meshcat calls to restart its loop after a recording
  var animator = Object.getPrototypeOf(viewer.animator), play = animator.play;
  animator.play = function () { play.call(this); ask(); };
  ask();
})();
// One message carries a frame's poses: paths and their 4x4 matrices (column-major), in a row.
var handle_one = viewer.handle_command.bind(viewer);
viewer.handle_command = function (command) {
  if (command.type !== "set_transforms") { return handle_one(command); }
  for (var i = 0; i < command.paths.length; i++) {
    handle_one({type: "set_transform", path: command.paths[i],
                matrix: command.matrices.subarray(16 * i, 16 * i + 16)});
  }
};
// The simulation draws its TF frames under /meshcat/tf, hidden; this box shows them.
// Drawn on top of the robot's shapes (no depth test): most frames sit inside the chassis.
document.getElementById("tf-frames").addEventListener("change", function (event) {
  var frames = viewer.scene_tree.find(["meshcat", "tf"]);
  frames.object.traverse(function (part) {
    if (part.material) { part.material.depthTest = false; part.renderOrder = 1; }
  });
  viewer.set_property(["meshcat", "tf"], "visible", event.target.checked);
});
// The websocket lives at the page's own prefix: "/" directly, "/proxy/<port>/" behind Jupyter.
var base = location.href.split(/[?#]/)[0].replace(/static\\/(index\\.html)?$/, "");
viewer.connect(base.replace(/^http/, "ws"));
// A view nobody can see (its notebook's tab in the background, scrolled out of sight, the
// browser tab hidden) tells the server so, which then sends it no poses until it is seen
// again. Frames drawn for a hidden view piled up and froze the page for 15-20 s when its
// notebook's tab came back. Chromium runs animation frames even in an iframe under
// `display: none`: what says "seen" is the pane's intersection with the top page's viewport.
var shown = true, visible = {pane: true, tab: true};
function tell(now) {
  shown = now;
  var socket = viewer.connection;
  if (socket && socket.readyState === 1) { socket.send(now ? "shown" : "hidden"); }
}
function update() {
  var now = visible.pane && visible.tab;
  if (now !== shown) { tell(now); }
}
new IntersectionObserver(function (entries) {
  visible.pane = entries[entries.length - 1].isIntersecting;
  update();
}).observe(document.getElementById("meshcat-pane"));
document.addEventListener("visibilitychange", function () {
  visible.tab = document.visibilityState === "visible";
  update();
});
if (viewer.connection) {
  viewer.connection.addEventListener("open", function () { if (!shown) { tell(false); } });
}
</script>
<script>
"""
    + PANEL_JS
    + 'accessiblePanel(viewer, document.getElementById("view-controls"));\n'
    + TOOLBAR_JS
    + ROBOT_STATE_JS
    + "</script></body></html>\n"
)


class _ViewerPage(tornado.web.RequestHandler):
    """meshcat's page, but connecting its websocket relative to where it was served from."""

    def get(self, _name: str = "") -> None:
        self.set_header("Cache-Control", "no-store")
        self.write(_PAGE)


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


def command_socket_url(pid: int | None = None) -> str:
    """Return the ZMQ address of this process's command socket: private to this user.

    Sockets that killed servers left are removed first (else one file per killed world, for
    ever: 1012 of them in a runtime folder after two days of tests).
    """
    remove_dead_command_sockets()
    path = runtime_dir() / f"meshcat-{pid or os.getpid()}.sock"
    path.unlink(missing_ok=True)  # a socket left by a killed server of a reused pid
    return f"ipc://{path}"


def remove_dead_command_sockets() -> list[Path]:
    """Remove the command sockets of servers that are gone; return them.

    Gone: no process has the pid in the file's name, and nothing answers on the socket (a
    server of another PID namespace sharing this folder still answers, and is kept).
    """
    removed = []
    for path in runtime_dir().glob("meshcat-*.sock"):
        pid = path.name.removeprefix("meshcat-").removesuffix(".sock")
        if not pid.isdigit() or procfs.pid_alive(int(pid)) or unix_socket_answers(path):
            continue
        path.unlink(missing_ok=True)
        removed.append(path)
    return removed


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
        self.websocket_pool = set()
        self.app = tornado.web.Application(
            [
                (r"/static/(index\.html)?", _ViewerPage),
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
        self.bridge.forward_poses(message)  # type: ignore[arg-type]

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
    loop = bridge.ioloop.asyncio_loop
    for signum in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(signum, bridge.ioloop.stop)
    try:
        bridge.run()
    finally:
        bridge.remove_command_socket()
    return 0


if __name__ == "__main__":
    sys.exit(main())
