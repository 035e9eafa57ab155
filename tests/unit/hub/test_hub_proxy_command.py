"""The class hub starts its proxy with the course's preload (keep-alive to Unix sockets), its
API on a Unix socket in the hub's own folder, and tells servers who holds the progress port."""

from __future__ import annotations

import os
from pathlib import Path
from urllib.parse import unquote

from jupyterhub.objects import Server
from traitlets.config import Config

from course_lib.core.host.scheduling import CLASS_HOST_ENV
from course_lib.hub.hub_config import configure
from course_lib.hub.plan import HubPlan
from course_lib.hub.progress import PROGRESS_HOLDER_ENV
from course_lib.hub.provision.proxy import PINS_DIR, PRELOAD, PROXY_API_SOCKET, proxy_command


def _configured(tmp_path: Path) -> Config:
    plan = HubPlan(
        ip="127.0.0.1",
        port=8000,
        hub_port=8081,
        progress_port=8090,
        authenticator="pam",
        learners=("alice",),
        admins=(),
        state=str(tmp_path / "state"),
        course=str(tmp_path / "course"),
        proxy_command=str(proxy_command(tmp_path / "environment")),
        idle_minutes=60,
    )
    c = Config()
    configure(c, plan)
    return c


def test_the_hub_runs_its_proxy_with_the_unix_keepalive_preload(tmp_path: Path) -> None:
    command = proxy_command(tmp_path / "environment")
    argv = _configured(tmp_path).ConfigurableHTTPProxy.command
    # python -m course_lib.hub.guard.tied --parent PID, then node --import <preload> <proxy>
    assert argv[1:3] == ["-m", "course_lib.hub.guard.tied"]
    assert argv[-3:] == ["--import", (command.parents[2] / PRELOAD).as_uri(), str(command)]
    assert Path(argv[-4]).name == "node"
    assert (PINS_DIR / PRELOAD).is_file()  # install_proxy copies it beside node_modules/


def test_the_proxys_api_is_a_unix_socket_in_the_hubs_state_folder(tmp_path: Path) -> None:
    """No API port: one picked free and released was another account's to bind first (it got
    the proxy's token). The state folder is root's alone (0700)."""
    url = _configured(tmp_path).ConfigurableHTTPProxy.api_url
    server = Server.from_url(url)  # as JupyterHub reads it: `--api-socket <path>` for the proxy
    assert server._unix_socket, url
    assert unquote(server.connect_addr) == str(tmp_path / "state" / PROXY_API_SOCKET)


def test_servers_are_told_which_account_holds_the_progress_port(tmp_path: Path) -> None:
    environment = _configured(tmp_path).Spawner.environment
    assert environment[PROGRESS_HOLDER_ENV] == str(os.getuid())  # the launcher's: root
    assert environment[CLASS_HOST_ENV] == "1"  # each learner's world yields to the commands
