"""The learners' image's server under the chart's hub: one JupyterHub release on both sides.

On Kubernetes the chart's hub (deploy/kubernetes/chart.yaml: hub_jupyterhub) starts a pod of
the learners' image, whose jupyterhub-singleuser is deploy/kubernetes/image-pins.txt's, and
reaches it over TCP. Here that release is installed beside the course's environment (its
dependencies are environment.txt's, as in the image) and runs both a hub and, through the
hub's spawner, the image's command, `python -m course_lib hub-lab`, in a home of its own. The
test reaches the server at the address the hub routes to (routing is the chart's proxy's job)
with the hub's token, as the proxy passes a learner's requests on.
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
import requests
from suite_env import TEST_ENV, independent_env

from course_lib.core.host.ports import free_port
from course_lib.core.host.procfs import environ
from course_lib.core.paths import REPO_ROOT, venv_bin_dir
from course_lib.core.waiting import wait_until
from course_lib.hub.singleuser import DEFAULT_URL, LEARNER_FOLDER
from course_lib.processes.children import ChildProcess, spawn

pytestmark = [pytest.mark.ros, pytest.mark.slow]

PINS = REPO_ROOT / "deploy" / "kubernetes" / "image-pins.txt"
LEARNER = "learner"
TOKEN = "chart-pairing-test-token-0123456789"
START_S = 180.0  # a lab (machine service, daemon, Jupyter server) on a busy 2-core host

# Read by the hub of the pinned release: a spawner that runs the image's command as a pod
# does (a home of its own, the same user here), tied to the hub so that it ends with it.
HUB_CONFIG = """\
import os
import sys

from jupyterhub.proxy import Proxy
from jupyterhub.spawner import SimpleLocalProcessSpawner

from course_lib.hub.guard.tied import tie_to_parent


class RoutesOnly(Proxy):
    \"\"\"Keep the routes the hub sets; the test goes to a route's target itself.\"\"\"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.routes = {{}}

    async def add_route(self, routespec, target, data):
        self.routes[routespec] = {{"routespec": routespec, "target": target, "data": data}}

    async def delete_route(self, routespec):
        self.routes.pop(routespec, None)

    async def get_all_routes(self):
        return dict(self.routes)


class PodSpawner(SimpleLocalProcessSpawner):
    \"\"\"The image's command in a home of its own; it ends with the hub.\"\"\"

    def make_preexec_fn(self, name):
        enter_home, hub = super().make_preexec_fn(name), os.getpid()

        def preexec():
            enter_home()
            tie_to_parent(parent=hub)

        return preexec


c.JupyterHub.proxy_class = RoutesOnly
c.Proxy.should_start = False
c.JupyterHub.ip = "127.0.0.1"
c.JupyterHub.port = {public_port}
c.JupyterHub.hub_ip = "127.0.0.1"
c.JupyterHub.hub_port = {hub_port}
c.JupyterHub.db_url = "sqlite:///{state}/jupyterhub.sqlite"
c.JupyterHub.cookie_secret_file = "{state}/cookie_secret"
c.JupyterHub.authenticator_class = "dummy"
c.JupyterHub.spawner_class = PodSpawner
c.PodSpawner.home_dir_template = "{homes}/{{username}}"
c.Spawner.cmd = [sys.executable, "-m", "course_lib", "hub-lab"]
c.Spawner.args = ["--allow-root"] if os.geteuid() == 0 else []  # a pod runs as uid 1000
c.Spawner.default_url = {default_url!r}
c.Spawner.environment = {environment!r}
c.Spawner.http_timeout = {start_s}
c.Spawner.start_timeout = {start_s}
c.JupyterHub.services = [{{"name": "checker", "api_token": {token!r}}}]
c.JupyterHub.load_roles = [
    {{
        "name": "checker",
        "scopes": ["admin:users", "admin:servers", "access:servers", "proxy"],
        "services": ["checker"],
    }}
]
"""


def _pin(name: str) -> str:
    found = re.search(rf"^{re.escape(name)}==(\S+)", PINS.read_text(), flags=re.MULTILINE)
    assert found, f"{PINS} pins no {name}"
    return found[1]


@pytest.fixture(scope="module")
def image_pins() -> Path:
    """Return a folder with image-pins.txt's packages, without their dependencies (the image
    installs them so over environment.txt); built once per clone and pins, kept."""
    text = PINS.read_bytes()
    digest = hashlib.sha1(str(REPO_ROOT).encode() + text).hexdigest()[:10]
    folder = Path(tempfile.gettempdir()) / f"ros2-course-image-pins-{digest}"
    with open(f"{folder}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not folder.is_dir():
            partial = Path(f"{folder}.partial")
            shutil.rmtree(partial, ignore_errors=True)
            into = ["--quiet", "--no-deps", "--target", str(partial), "-r", str(PINS)]
            uv = [str(venv_bin_dir() / "uv"), "pip", "install", "--python", sys.executable]
            if subprocess.run([*uv, *into], check=False).returncode != 0:  # as `make setup`:
                shutil.rmtree(partial, ignore_errors=True)  # pip where only pip reaches them
                subprocess.run([sys.executable, "-m", "pip", "install", *into], check=True)
            partial.rename(folder)
    return folder


def _hub_api(hub_url: str, method: str, path: str) -> requests.Response:
    headers = {"Authorization": f"token {TOKEN}"}
    return requests.request(method, f"{hub_url}/hub/api{path}", headers=headers, timeout=30)


def _learners_processes(homes: Path) -> list[int]:
    """Return the live processes whose HOME is a learner's home of this test."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit() and environ(int(entry.name)).get("HOME", "").startswith(
            f"{homes}/"
        ):
            found.append(int(entry.name))
    return found


@pytest.fixture
def chart_hub(image_pins: Path, tmp_path: Path) -> Iterator[tuple[str, Path, ChildProcess]]:
    """Yield a hub of the pinned release (its URL, the learners' homes, its process)."""
    state, homes = tmp_path / "state", tmp_path / "homes"
    state.mkdir()
    homes.mkdir()
    hub_port = free_port()
    config = tmp_path / "jupyterhub_config.py"
    config.write_text(
        HUB_CONFIG.format(
            public_port=free_port(),
            hub_port=hub_port,
            state=state,
            homes=homes,
            default_url=DEFAULT_URL,
            environment=TEST_ENV,
            start_s=int(START_S),
            token=TOKEN,
        )
    )
    env = independent_env(PYTHONPATH=str(image_pins))  # the hub passes PYTHONPATH on
    argv = [sys.executable, "-m", "jupyterhub", "-f", str(config)]
    hub = spawn(argv, name="chart-hub", env=env, cwd=tmp_path, merge_stderr=True)
    hub_url = f"http://127.0.0.1:{hub_port}"
    try:

        def answers() -> bool:
            try:
                return requests.get(f"{hub_url}/hub/api/", timeout=5).ok
            except requests.ConnectionError:
                return False

        assert wait_until(answers, 60.0), f"the hub did not start:\n{hub.text()[-3000:]}"
        yield hub_url, homes, hub
    finally:
        if hub.alive:
            hub.send_signal(signal.SIGINT)  # the hub stops the servers it started
            hub.wait(60.0)
        hub.stop(timeout=5.0)
        left = _learners_processes(homes)
        for pid in left:  # only what this test's hub started for its learner
            os.kill(pid, signal.SIGKILL)
        assert not left, f"the learner's processes outlived the hub: {left}"


def test_the_images_server_runs_under_the_charts_hub(
    chart_hub: tuple[str, Path, ChildProcess],
) -> None:
    hub_url, homes, hub = chart_hub
    release = _pin("jupyterhub")
    assert requests.get(f"{hub_url}/hub/api/", timeout=5).json()["version"] == release
    assert _hub_api(hub_url, "POST", f"/users/{LEARNER}").status_code == 201
    assert _hub_api(hub_url, "POST", f"/users/{LEARNER}/server").status_code in (201, 202)

    def ready() -> bool:
        server = _hub_api(hub_url, "GET", f"/users/{LEARNER}").json()["servers"].get("", {})
        return bool(server.get("ready"))

    assert wait_until(ready, START_S + 10), f"no server:\n{hub.text()[-4000:]}"
    route = _hub_api(hub_url, "GET", "/proxy").json()[f"/user/{LEARNER}/"]
    base = f"{route['target']}/user/{LEARNER}"
    headers = {"Authorization": f"token {TOKEN}"}

    status = requests.get(f"{base}/api/status", headers=headers, timeout=30)
    assert status.ok, status.text
    log = hub.text()
    assert f"single-user server extension version {release}" in log, log[-4000:]
    # the learner's copy of the lessons, in the home the pod's volume would be, is the root
    assert (homes / LEARNER / LEARNER_FOLDER / "notebooks" / "01_setup_check.ipynb").is_file()
    lessons = requests.get(f"{base}/api/contents/notebooks", headers=headers, timeout=30)
    assert lessons.ok, lessons.text
    names = {item["name"] for item in lessons.json()["content"]}
    assert "01_setup_check.ipynb" in names, names
    page = requests.get(f"{base}{DEFAULT_URL}", headers=headers, timeout=30)
    assert page.ok and "jupyter-config-data" in page.text, page.text[:2000]
    assert "!= jupyterhub-singleuser version" not in hub.text(), hub.text()[-4000:]

    assert _hub_api(hub_url, "DELETE", f"/users/{LEARNER}/server").status_code in (202, 204)
    assert wait_until(lambda: not _learners_processes(homes), 30.0), (
        f"left after the hub stopped the server: {_learners_processes(homes)}"
    )
