"""The 3D view in a notebook cell: a meshcat server owned by the session, shown in an iframe.

The server is the simulation process itself (`Viewer.served_by`, `sim.launcher`).

How the browser reaches the server (the iframe's address):
- "proxy": through jupyter-server-proxy, `<base_url>proxy/<port>/static/`, so it works when
  JupyterLab is remote (JupyterHub, SSH, containers); the viewer's websocket goes the same way.
- "direct": `http://127.0.0.1:<port>/static/`, only for a browser on the kernel's machine.
Default "auto": proxy when jupyter-server-proxy is installed, else direct. Override with the
environment variable COURSE_VIEWER_URL (proxy|direct); JupyterHub's JUPYTERHUB_SERVICE_PREFIX
(or COURSE_JUPYTER_BASE_URL) gives the base URL, "/" otherwise.
"""

from __future__ import annotations

import html
import importlib.util
import os
import re
from typing import Any

from ..core.files.live_outputs import LIVE_MARK
from ..core.server_urls import jupyter_base_url

__all__ = ["Viewer", "viewer_url"]

_URL_MODE_ENV = "COURSE_VIEWER_URL"


def viewer_url(port: int, mode: str | None = None, environ: dict[str, str] | None = None) -> str:
    """Return the address the notebook's browser should load for a server on `port`."""
    env = os.environ if environ is None else environ
    mode = mode or env.get(_URL_MODE_ENV, "auto")
    if mode == "auto":
        mode = "proxy" if importlib.util.find_spec("jupyter_server_proxy") else "direct"
    if mode == "direct":
        return f"http://127.0.0.1:{port}/static/"
    return f"{jupyter_base_url(env)}proxy/{port}/static/"


class Viewer:
    """The process serving a meshcat view, and the iframe that shows it."""

    def __init__(self, process: Any, zmq_url: str, port: int) -> None:
        self.process = process
        self.zmq_url = zmq_url
        self.port = port

    @classmethod
    def served_by(cls, process: Any, timeout: float) -> Viewer | None:
        """Return the view a process serves, from its `zmq_url=` and `web_url=` lines."""
        line = process.wait_for_line(r"^web_url=", timeout)
        zmq = next((ln.text for ln in process.lines if ln.text.startswith("zmq_url=")), None)
        if line is None or zmq is None:
            return None
        port = re.search(r":(\d+)/static/", line.text)
        if port is None:
            return None
        return cls(process, zmq.split("=", 1)[1], int(port.group(1)))

    @property
    def url(self) -> str:
        """Return the iframe's address (see the module docstring)."""
        return viewer_url(self.port)

    def iframe_html(self, height: int = 420) -> str:
        """Return the HTML of the view's iframe."""
        src = html.escape(self.url, quote=True)
        return (
            f'<div {LIVE_MARK}="3D view" '
            f'style="height: {height}px; width: 100%; resize: both; overflow: hidden">'
            f'<iframe src="{src}" title="3D view of the simulated robot" '
            'style="width: 100%; height: 100%; border: none"></iframe></div>'
        )

    def show(self, height: int = 420) -> Any:
        """Display the view in the current output cell."""
        from IPython.display import HTML, display

        view = HTML(self.iframe_html(height))
        display(view)
        return view

    def stop(self) -> None:
        """Stop the server; idempotent."""
        self.process.stop()
