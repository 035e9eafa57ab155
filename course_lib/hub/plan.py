"""Everything the hub's configuration needs, resolved before anything starts (ports, paths)."""

from __future__ import annotations

import dataclasses
import json
import os
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import quote

from .provision.proxy import PROXY_API_SOCKET

__all__ = ["PLAN_ENV", "HubPlan", "read_plan", "write_plan"]

PLAN_ENV = "COURSE_HUB_PLAN"  # names the plan file for jupyterhub_config.py


@dataclass(frozen=True)
class HubPlan:
    """One start of the class hub: what jupyterhub_config.py turns into JupyterHub settings."""

    ip: str
    port: int
    hub_port: int
    progress_port: int
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
        return "http+unix://" + quote(str(Path(self.state) / PROXY_API_SOCKET), safe="")


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
