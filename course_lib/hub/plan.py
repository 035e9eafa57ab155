"""Everything the hub's configuration needs, resolved before anything starts (ports, paths)."""

from __future__ import annotations

import dataclasses
import json
import os
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import quote

from .provision.proxy import PROXY_API_SOCKET

__all__ = [
    "HUB_SOCKET",
    "PLAN_ENV",
    "PROGRESS_SOCKET",
    "PROXY_SOCKET",
    "HubPlan",
    "read_plan",
    "write_plan",
]

PLAN_ENV = "COURSE_HUB_PLAN"  # names the plan file for jupyterhub_config.py
# In the state folder (root's alone), behind the launcher's gate (course_lib.hub.guard.gate),
# which holds the hub's TCP ports: the proxy's public side, JupyterHub's API, the progress
# service.
PROXY_SOCKET = "proxy.sock"
HUB_SOCKET = "hub.sock"
PROGRESS_SOCKET = "progress.sock"


@dataclass(frozen=True)
class HubPlan:
    """One start of the class hub: what jupyterhub_config.py turns into JupyterHub settings."""

    ip: str
    port: int
    hub_port: int  # JupyterHub's API and the progress service: TCP ports the launcher's gate
    progress_port: int  # holds, doors to HUB_SOCKET and PROGRESS_SOCKET
    authenticator: str
    learners: tuple[str, ...]
    admins: tuple[str, ...]
    state: str  # the hub's database, cookie secret, progress records (root only)
    course: str  # the learners' copy of the course
    proxy_command: str
    idle_minutes: int
    shared_password: str | None = None
    admin_password: str | None = None
    wall: bool = False  # each learner's server in a network of its own (course_lib.hub.guard.wall)
    sockets: str = ""  # with the wall: the folder of the learners' server socket folders
    progress_token: str = ""  # the progress service's API token (the launcher starts it)

    @property
    def learner_python(self) -> str:
        """Return the interpreter of the learners' environment."""
        return str(Path(self.course) / ".venv" / "bin" / "python")

    @property
    def proxy_api_url(self) -> str:
        """Return the proxy's API address, http+unix://<its socket in the state folder>."""
        return self.socket_url(PROXY_API_SOCKET)

    def socket_url(self, name: str) -> str:
        """Return http+unix://<the socket `name` in the state folder>."""
        return "http+unix://" + quote(str(Path(self.state) / name), safe="")

    @property
    def hub_api_url(self) -> str:
        """Return JupyterHub's API at its TCP port (the gate's), for servers and services."""
        return f"http://127.0.0.1:{self.hub_port}/hub/api"


def write_plan(plan: HubPlan, path: Path) -> Path:
    """Write `plan` as JSON readable by root only (it may hold the demo's passwords)."""
    partial = path.with_suffix(".partial")
    fd = os.open(partial, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(fd, "w", encoding="utf-8") as out:
        json.dump(dataclasses.asdict(plan), out, indent=1)
    partial.replace(path)
    return path


def read_plan(path: str | Path) -> HubPlan:
    """Read a plan written by write_plan."""
    data = json.loads(Path(path).read_text(encoding="utf-8"))
    data["learners"] = tuple(data["learners"])
    data["admins"] = tuple(data["admins"])
    return HubPlan(**data)
