"""A real JupyterHub for the tests: the course's progress service, three learners, one admin.

The hub runs from this environment (`python -m jupyterhub`) with configurable-http-proxy from
npm, the shared-password authenticator, and a stand-in single-user server
(fake_singleuser.py) so that each learner gets a real server token from a real spawn. The
progress service runs as the class hub runs it: on a socket bound before the hub starts,
handed over (course_lib.hub.progress_service), as this process's user.
"""

from __future__ import annotations

import contextlib
import json
import os
import secrets
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any
from urllib.parse import quote

import requests
from hub_sign_in import sign_in

from course_lib.core.host.ports import free_port
from course_lib.hub.progress import (
    PROGRESS_HOLDER_ENV,
    PROGRESS_URL_ENV,
    SERVICE_NAME,
    roles,
    service_environment,
    service_spec,
)
from course_lib.hub.progress_service import bind_service_socket, start_service, stop_service
from course_lib.hub.provision.proxy import PROXY_API_SOCKET, install_proxy
from course_lib.processes.children import set_parent_death_signal

LEARNERS = ("alice", "bob", "carol")
ADMIN = "teacher"
PASSWORD = "learners-share-this"  # shared-password: at least 8 characters
ADMIN_PASSWORD = "the-admin-password-is-32-characters-or-more"
HERE = Path(__file__).resolve().parent


def proxy_command(cache: Path) -> str:
    """Return the course's pinned configurable-http-proxy, installed from npm once into `cache`
    (shared by the xdist workers: install_proxy installs one at a time)."""
    return str(install_proxy(cache))


def _die_with_parent() -> None:
    set_parent_death_signal(signal.SIGTERM, os.getppid())


class ClassHub:
    """One hub in `root` (its database, cookie secret, log and the progress records)."""

    def __init__(self, root: Path, proxy: str) -> None:
        self.root = root
        self.proxy = proxy
        self.port, self.hub_port = free_port(), free_port()
        self.listener = bind_service_socket()  # held across restarts, until close()
        self.service_port = self.listener.getsockname()[1]
        self.service_token = secrets.token_hex(32)
        self.service: subprocess.Popen[bytes] | None = None
        self.db = root / "state" / "progress.sqlite"
        self.servers_out = root / "servers"
        self.token = secrets.token_hex(16)  # the tests' own service token
        self.log = root / "hub.log"
        self.process: subprocess.Popen[bytes] | None = None
        (root / "jupyterhub_config.py").write_text(self._config())

    @property
    def url(self) -> str:
        """Return the hub's public URL (through the proxy), without a trailing slash."""
        return f"http://127.0.0.1:{self.port}"

    @property
    def service_url(self) -> str:
        """Return the progress service's direct URL, as learners' servers get it."""
        return f"http://127.0.0.1:{self.service_port}/services/{SERVICE_NAME}/"

    def _config(self) -> str:
        spec = service_spec(self.service_port, self.service_token)
        tests = {"name": "course-tests", "api_token": self.token}
        tests_role = {
            "name": "course-tests",
            "scopes": ["admin:users", "admin:servers", "read:roles"],
            "services": ["course-tests"],
        }
        settings = {
            "JupyterHub.ip": "127.0.0.1",
            "JupyterHub.port": self.port,
            "JupyterHub.hub_ip": "127.0.0.1",
            "JupyterHub.hub_port": self.hub_port,
            "JupyterHub.db_url": f"sqlite:///{self.root / 'state' / 'jupyterhub.sqlite'}",
            "JupyterHub.cookie_secret_file": str(self.root / "state" / "cookie_secret"),
            "JupyterHub.cleanup_servers": True,
            "JupyterHub.services": [spec, tests],
            "JupyterHub.load_roles": [*roles(), tests_role],
            "ConfigurableHTTPProxy.api_url": "http+unix://"
            + quote(str(self.root / "state" / PROXY_API_SOCKET), safe=""),
            "ConfigurableHTTPProxy.pid_file": str(self.root / "state" / "proxy.pid"),
            "JupyterHub.authenticator_class": "shared-password",
            "SharedPasswordAuthenticator.user_password": PASSWORD,
            "SharedPasswordAuthenticator.admin_password": ADMIN_PASSWORD,
            "Authenticator.allowed_users": {*LEARNERS, ADMIN},
            "Authenticator.admin_users": {ADMIN},
            "JupyterHub.spawner_class": "simple",
            "SimpleLocalProcessSpawner.home_dir_template": str(self.root / "homes" / "{username}"),
            "Spawner.cmd": [sys.executable, str(HERE / "fake_singleuser.py")],
            "Spawner.environment": {
                PROGRESS_URL_ENV: self.service_url,
                PROGRESS_HOLDER_ENV: str(os.getuid()),  # this process holds its port
                "FAKE_SERVER_OUT": str(self.servers_out),
            },
        }
        lines = [f"c.{key} = {value!r}" for key, value in settings.items()]
        # tied to the hub, as in the class hub: the command names its parent, the hub, so it
        # is written in the hub's own process, where this file runs
        lines += [
            "from course_lib.hub.provision.proxy import proxy_argv",
            "from course_lib.hub.guard.tied import tied_command",
            f"c.ConfigurableHTTPProxy.command = tied_command(*proxy_argv({self.proxy!r}))",
        ]
        return "c = get_config()  # noqa: F821\n" + "\n".join(lines) + "\n"

    # --- the hub process ----------------------------------------------------------------------
    def start(self, timeout: float = 60.0) -> None:
        """Start the hub and wait until it and the progress service answer."""
        (self.root / "state").mkdir(exist_ok=True)
        api = f"http://127.0.0.1:{self.hub_port}/hub/api"
        environment = service_environment(self.service_port, self.service_token, api)
        self.service = start_service(sys.executable, self.db, self.listener, environment)
        with open(self.log, "ab") as log:
            self.process = subprocess.Popen(
                [sys.executable, "-m", "jupyterhub", "-f", "jupyterhub_config.py"],
                cwd=self.root, stdout=log, stderr=subprocess.STDOUT,
                preexec_fn=_die_with_parent,
            )  # fmt: skip
        deadline = time.monotonic() + timeout
        through_proxy = f"{self.url}/services/{SERVICE_NAME}/api/records"
        while not (
            self._status(f"{self.url}/hub/api/") == 200 and self._status(through_proxy) == 401
        ):
            if self.process.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"the hub did not come up; its log ends:\n{self.log_tail()}")
            time.sleep(0.2)

    @staticmethod
    def _status(url: str) -> int:
        with contextlib.suppress(requests.RequestException):
            return requests.get(url, timeout=2, allow_redirects=False).status_code
        return 0

    def stop(self) -> None:
        """Stop the hub (it stops the proxy and every server), then the progress service."""
        if self.service is not None:
            stop_service(self.service)
            self.service = None
        if self.process is None:
            return
        self.process.send_signal(signal.SIGTERM)
        try:
            self.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self.process = None

    def close(self) -> None:
        """Stop the hub and free the progress service's port, held across restarts until now."""
        self.stop()
        self.listener.close()

    def log_tail(self, lines: int = 40) -> str:
        """Return the end of the hub's log (for failure messages)."""
        text = self.log.read_text(errors="replace") if self.log.exists() else ""
        return "\n".join(text.splitlines()[-lines:])

    def service_pid(self) -> int:
        """Return the pid of the progress service."""
        assert self.service is not None
        return self.service.pid

    # --- the hub's REST API, with the tests' service token ------------------------------------
    def api(self, method: str, path: str, **kwargs: Any) -> requests.Response:
        """Call the hub's REST API (`path` after /hub/api/) as the tests' service."""
        headers = {"Authorization": f"token {self.token}"}
        return requests.request(
            method, f"{self.url}/hub/api/{path}", headers=headers, timeout=30, **kwargs
        )

    def spawn(self, user: str, timeout: float = 60.0) -> dict[str, str]:
        """Start `user`'s server; return what it got: its token, user and progress URL."""
        out = self.servers_out / f"{user}.json"
        out.unlink(missing_ok=True)
        answer = self.api("POST", f"users/{user}/server")
        assert answer.status_code in (201, 202), answer.text
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            model = self.api("GET", f"users/{user}").json()
            server = model.get("servers", {}).get("", {})
            if server.get("ready") and out.exists():
                return json.loads(out.read_text())
            time.sleep(0.2)
        raise RuntimeError(
            f"{user}'s server did not start; the hub's log ends:\n{self.log_tail()}"
        )

    def login(self, user: str, password: str) -> requests.Session:
        """Return a browser-like session logged in to the hub as `user` (the login form)."""
        session, done = sign_in(self.url, user, password)
        assert done.ok and "/hub/login" not in done.url, f"{user} could not log in: {done.url}"
        return session
