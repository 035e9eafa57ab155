"""The class hub's JupyterHub settings, from a HubPlan (read by jupyterhub_config.py)."""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

from ..core.host.scheduling import CLASS_HOST_ENV
from .guard.tied import tied_command
from .plan import HUB_SOCKET, PROXY_SOCKET, HubPlan
from .provision.proxy import proxy_argv
from .singleuser import DEFAULT_URL

__all__ = ["configure"]

LEARNER_PATH = "/usr/local/bin:/usr/bin:/bin"


def _progress(plan: HubPlan) -> tuple[list[dict[str, Any]], list[dict[str, Any]], dict[str, str]]:
    """Return the progress service, its roles and the environment it gives learners' servers
    (the launcher runs the service: course_lib/hub/progress_service.py)."""
    from .progress import PROGRESS_HOLDER_ENV, PROGRESS_URL_ENV, SERVICE_NAME, roles, service_spec

    spec = service_spec(plan.progress_port, plan.progress_token)
    url = f"http://127.0.0.1:{plan.progress_port}/services/{SERVICE_NAME}/"
    # the launcher holds the port, as the account the hub runs as: a kernel sends its token
    # to that port only while it is theirs (course_lib/lessons/progress/client.py)
    return [spec], roles(), {PROGRESS_URL_ENV: url, PROGRESS_HOLDER_ENV: str(os.getuid())}


def _idle_culler(plan: HubPlan) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    if plan.idle_minutes <= 0:
        return [], []
    service = {
        "name": "idle-culler",
        "command": tied_command(sys.executable, "-m", "jupyterhub_idle_culler",
                         f"--timeout={plan.idle_minutes * 60}", f"--url={plan.hub_api_url}"),
    }  # fmt: skip
    role = {
        "name": "idle-culler",
        "scopes": ["list:users", "read:users:activity", "read:servers", "delete:servers"],
        "services": ["idle-culler"],
    }
    return [service], [role]


def configure(c: Any, plan: HubPlan) -> None:
    """Fill JupyterHub's config object `c` for the class described by `plan`."""
    state = Path(plan.state)
    # JupyterHub and its proxy listen on Unix sockets only root reaches; the launcher holds
    # the TCP ports (plan.port, plan.hub_port) and counts each account's connections there
    c.JupyterHub.bind_url = plan.socket_url(PROXY_SOCKET)
    c.JupyterHub.hub_bind_url = c.JupyterHub.hub_connect_url = plan.socket_url(HUB_SOCKET)
    c.Spawner.hub_connect_url = plan.hub_api_url.removesuffix("/hub/api")
    c.JupyterHub.db_url = f"sqlite:///{state / 'jupyterhub.sqlite'}"
    c.JupyterHub.cookie_secret_file = str(state / "jupyterhub_cookie_secret")
    c.JupyterHub.cleanup_servers = True  # the hub stopping stops every learner's server
    c.ConfigurableHTTPProxy.api_url = plan.proxy_api_url  # a socket only root reaches
    c.ConfigurableHTTPProxy.command = tied_command(*proxy_argv(plan.proxy_command))
    c.ConfigurableHTTPProxy.pid_file = str(state / "proxy.pid")

    c.JupyterHub.authenticator_class = plan.authenticator
    c.Authenticator.allowed_users = set(plan.learners) | set(plan.admins)
    c.Authenticator.admin_users = set(plan.admins)
    if plan.authenticator == "shared-password":
        c.SharedPasswordAuthenticator.user_password = plan.shared_password
        c.SharedPasswordAuthenticator.admin_password = plan.admin_password

    services, roles, server_env = _progress(plan)
    culler, culler_roles = _idle_culler(plan)
    c.JupyterHub.services = services + culler
    c.JupyterHub.load_roles = roles + culler_roles

    c.JupyterHub.spawner_class = "course_lib.hub.spawner.CourseSpawner"
    c.Spawner.cmd = [plan.learner_python, "-m", "course_lib", "hub-lab"]
    c.Spawner.default_url = DEFAULT_URL
    c.Spawner.env_keep = ["LANG", "LC_ALL"]  # nothing of root's environment (its venv, PATH)
    venv_bin = str(Path(plan.learner_python).parent)
    c.Spawner.environment = {
        "PATH": f"{venv_bin}:{LEARNER_PATH}",
        CLASS_HOST_ENV: "1",  # a class's host: each world yields to the learners' commands
        **server_env,
    }
    c.Spawner.start_timeout = 120
    c.CourseSpawner.wall = plan.wall
    c.CourseSpawner.sockets_dir = plan.sockets
    c.CourseSpawner.state_dir = plan.state  # its record of whose runtime folders are whose
    c.CourseSpawner.relay_ports = [plan.hub_port, plan.progress_port]  # the API, progress
    c.Spawner.http_timeout = 120
    from .spawner import stop_leftovers_hook  # imports JupyterHub: the hub's side only

    c.Spawner.post_stop_hook = stop_leftovers_hook
