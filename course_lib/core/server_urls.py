"""Addresses, in the learner's browser, of what the course's Jupyter server serves (pure).

A lab or a hub learner's server exports the folder it serves (`SERVER_ROOT_ENV`) to its
kernels, so a lesson can link a file raw: Jupyter Server's `files/` handler sends an HTML page
with a `sandbox allow-scripts` policy, so its scripts run in an origin of their own, apart from
the lab's. JupyterLab would open a relative link in its HTML viewer instead, scripts off.
"""

from __future__ import annotations

import os
import urllib.parse
from collections.abc import Mapping
from pathlib import Path

__all__ = ["SERVER_ROOT_ENV", "jupyter_base_url", "served_file_url"]

SERVER_ROOT_ENV = "COURSE_SERVER_ROOT"


def jupyter_base_url(environ: Mapping[str, str] | None = None) -> str:
    """Return the server's base URL path, ending in `/` (a hub learner's `/user/<name>/`)."""
    env = os.environ if environ is None else environ
    base = env.get("JUPYTERHUB_SERVICE_PREFIX") or env.get("COURSE_JUPYTER_BASE_URL") or "/"
    return base.rstrip("/") + "/"


def served_file_url(path: Path, environ: Mapping[str, str] | None = None) -> str | None:
    """Return the address of `path` under the server's `files/` handler, or None when no
    course server runs this process (a plain kernel, nbval) or `path` is outside its folder."""
    env = os.environ if environ is None else environ
    root = env.get(SERVER_ROOT_ENV)
    if not root:
        return None
    try:
        inside = path.resolve().relative_to(Path(root).resolve())
    except ValueError:
        return None
    return f"{jupyter_base_url(env)}files/{urllib.parse.quote(inside.as_posix())}"
