"""The meshcat server as a child of the course session: 127.0.0.1, free ports, no leak.

Run as `python -m course_lib.viz.server`; it prints `zmq_url=...` and `web_url=...` once it
listens, then serves until it is stopped (the session stops it, or it dies with the kernel).
meshcat-python's own `Visualizer()` would start a server that outlives a killed kernel.
"""

from __future__ import annotations

import argparse
import signal
import sys

import tornado.httpserver
import tornado.ioloop
import tornado.netutil
import tornado.web
import zmq
from meshcat.servers.tree import SceneTree
from meshcat.servers.zmqserver import (
    VIEWER_HTML,
    VIEWER_ROOT,
    StaticFileHandlerNoCache,
    WebSocketHandler,
    ZMQWebSocketBridge,
)

__all__ = ["LocalBridge", "main"]


_PAGE = """<!DOCTYPE html>
<html><head><meta charset=utf-8><title>MeshCat</title>
<style>body {margin: 0} #meshcat-pane {width: 100vw; height: 100vh; overflow: hidden}
#tf-toggle {position: absolute; left: 8px; top: 8px; padding: 2px 6px; border-radius: 4px;
  font: 13px sans-serif; color: #fff; background: rgba(0, 0, 0, 0.55); user-select: none}</style>
</head><body><div id="meshcat-pane"></div>
<label id="tf-toggle" title="the frames /tf and /tf_static describe (x red, y green, z blue)">
<input type="checkbox" id="tf-frames"> TF frames</label>
<script src="main.min.js"></script>
<script>
var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));
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
</script></body></html>
"""


class _ViewerPage(tornado.web.RequestHandler):
    """meshcat's page, but connecting its websocket relative to where it was served from."""

    def get(self, _name: str = "") -> None:
        self.set_header("Cache-Control", "no-store")
        self.write(_PAGE)


class _AnyOriginWebSocket(WebSocketHandler):
    """Accept the viewer page whichever origin serves it (direct, or a Jupyter proxy)."""

    def check_origin(self, origin: str) -> bool:
        return True


class LocalBridge(ZMQWebSocketBridge):
    """meshcat's bridge bound to one host, on ports the operating system picks."""

    def __init__(self, host: str = "127.0.0.1", port: int = 0) -> None:
        self.host = host
        self.websocket_pool = set()
        self.app = tornado.web.Application(
            [
                (r"/static/(index\.html)?", _ViewerPage),
                (
                    r"/static/(.*)",
                    StaticFileHandlerNoCache,
                    {"path": VIEWER_ROOT, "default_filename": VIEWER_HTML},
                ),
                (r"/", _AnyOriginWebSocket, {"bridge": self}),
            ]
        )
        self.ioloop = tornado.ioloop.IOLoop.current()
        self.zmq_socket, self.zmq_stream, _ = self.setup_zmq(f"tcp://{host}:*")
        self.zmq_url = self.zmq_socket.getsockopt(zmq.LAST_ENDPOINT).decode()
        sockets = tornado.netutil.bind_sockets(port, address=host)
        server = tornado.httpserver.HTTPServer(self.app)
        server.add_sockets(sockets)
        self.fileserver_port = sockets[0].getsockname()[1]
        self.web_url = f"http://{host}:{self.fileserver_port}/static/"
        self.tree = SceneTree()


def main(argv: list[str] | None = None) -> int:
    """Serve until SIGINT or SIGTERM."""
    parser = argparse.ArgumentParser(description="meshcat server for the course (127.0.0.1)")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=0, help="web port (0: a free one)")
    args = parser.parse_args(argv)
    bridge = LocalBridge(args.host, args.port)
    print(f"zmq_url={bridge.zmq_url}", flush=True)
    print(f"web_url={bridge.web_url}", flush=True)

    # asyncio's own handlers wake the loop even when a zmq thread receives the signal; a plain
    # signal.signal() handler would wait for an event that never comes.
    loop = bridge.ioloop.asyncio_loop
    for signum in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(signum, bridge.ioloop.stop)
    bridge.run()
    return 0


if __name__ == "__main__":
    sys.exit(main())
