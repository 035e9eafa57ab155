"""The address a learner opens to see turtlesim's window (pure)."""

from __future__ import annotations

import importlib.util
import os
from collections.abc import Mapping

__all__ = ["window_url"]


def window_url(port: int, environ: Mapping[str, str] | None = None) -> str:
    """Return where the learner's browser reaches a window served on 127.0.0.1:`port`.

    In a lab's terminal (JupyterLab sets JUPYTER_SERVER_URL there) it is the lab's own
    address through jupyter-server-proxy, `<lab>/proxy/<port>/`, so a remote lab works too; on
    JupyterHub, the path under the learner's server. Elsewhere, the port itself.
    """
    env = os.environ if environ is None else environ
    direct = f"http://127.0.0.1:{port}/"
    if env.get("COURSE_VIEWER_URL") == "direct" or not _has_proxy():
        return direct
    hub = env.get("JUPYTERHUB_SERVICE_PREFIX")
    if hub:
        return f"{hub.rstrip('/')}/proxy/{port}/"
    server = env.get("JUPYTER_SERVER_URL")
    if server:
        return f"{server.rstrip('/')}/proxy/{port}/"
    return direct


def _has_proxy() -> bool:
    return importlib.util.find_spec("jupyter_server_proxy") is not None
