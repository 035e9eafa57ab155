"""Serve turtlesim's window on 127.0.0.1: the page at `/`, the current SVG at `/view.svg`."""

from __future__ import annotations

import threading
from collections.abc import Callable
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

from .page import window_page
from .scene import Scene
from .svg import render_svg

__all__ = ["WindowServer"]


class WindowServer:
    """An HTTP server in a daemon thread that draws `scene()` at every request.

    It listens at once (so its address can be printed before the node starts) and answers
    503 until `show` gives it the node's scene.
    """

    def __init__(self) -> None:
        self.scene: Callable[[], Scene] | None = None
        self.node = "/turtlesim"
        self._http = ThreadingHTTPServer(("127.0.0.1", 0), _handler(self))
        self._http.daemon_threads = True
        self.port: int = self._http.server_address[1]
        self._thread = threading.Thread(
            target=self._http.serve_forever, name="turtlesim-window", daemon=True
        )
        self._thread.start()

    def show(self, scene: Callable[[], Scene], node: str) -> None:
        """Draw `scene()` from now on, for the node named `node`."""
        self.node = node
        self.scene = scene

    def stop(self) -> None:
        """Stop serving; idempotent."""
        if self._thread.is_alive():
            self._http.shutdown()
            self._thread.join()
        self._http.server_close()


def _handler(window: WindowServer) -> type[BaseHTTPRequestHandler]:
    class Handler(BaseHTTPRequestHandler):
        def do_GET(self) -> None:
            path = self.path.split("?", 1)[0]
            if path not in ("/", "/index.html", "/view.svg"):
                self.send_error(404)
            elif window.scene is None:
                self.send_error(503, "turtlesim is starting: reload in a moment")
            elif path == "/view.svg":
                self._reply(render_svg(window.scene()), "image/svg+xml")
            else:
                self._reply(window_page(render_svg(window.scene()), window.node), "text/html")

        def _reply(self, text: str, content_type: str) -> None:
            body = text.encode()
            self.send_response(200)
            self.send_header("Content-Type", f"{content_type}; charset=utf-8")
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, format: str, *args: object) -> None:
            """Stay quiet: the node's terminal shows the node's log only."""

    return Handler
