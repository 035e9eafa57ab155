"""The class hub's progress service: its port is held from the moment it is chosen for the
hub's whole life (no other process can take it before the service listens, nor after it
dies: it starts again on the same socket, at a bounded rate), and it runs as an account of
its own."""

from __future__ import annotations

import os
import pwd
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import requests
from class_hub import hub_environment, start_prebuild

from course_lib.core.host.procfs import pid_alive
from course_lib.core.paths import REPO_ROOT
from course_lib.core.waiting import wait_until
from course_lib.hub.launcher import NO_WALL_ENV, _plan
from course_lib.hub.progress import SERVICE_NAME, service_environment
from course_lib.hub.progress_service import (
    SERVICE_ACCOUNT,
    KeptService,
    bind_service_socket,
    records_folder,
    start_service,
    stop_service,
)
from course_lib.hub.provision.accounts import ensure_system_account
from course_lib.hub.provision.settings import HubSettings

ROOT_ONLY = pytest.mark.skipif(os.geteuid() != 0, reason="an account of its own needs root")


def test_the_plan_names_a_port_already_held_for_the_service(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(NO_WALL_ENV, "1")
    settings = HubSettings(learners=("ada",), admins=("bea",))
    with bind_service_socket() as listener:
        plan = _plan(settings, tmp_path, tmp_path / "course", tmp_path / "proxy", listener)
        port = plan.progress_port
        # listening already: a picked-then-released port would refuse here (and be free to
        # whoever binds it first)
        socket.create_connection(("127.0.0.1", port), timeout=2).close()
        with socket.socket() as squatter, pytest.raises(OSError):
            squatter.bind(("127.0.0.1", port))
    assert len(plan.progress_token) >= 32


_LAUNCHER = """
import sys
from pathlib import Path
from course_lib.hub.progress import service_environment
from course_lib.hub.progress_service import bind_service_socket, start_service
listener = bind_service_socket()
port = listener.getsockname()[1]
environment = service_environment(port, "t" * 64, "http://127.0.0.1:9/hub/api")
service = start_service(sys.executable, Path(sys.argv[1]), listener, environment)
print(service.pid, flush=True)
sys.stdin.read()
"""


def test_a_killed_launcher_leaves_no_service(tmp_path: Path) -> None:
    launcher = subprocess.Popen(
        [sys.executable, "-c", _LAUNCHER, str(tmp_path / "progress.sqlite")],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, cwd=REPO_ROOT,
    )  # fmt: skip
    try:
        assert launcher.stdout is not None
        service = int(launcher.stdout.readline())
        launcher.kill()
        launcher.wait(10)
        deadline = time.monotonic() + 15.0
        while pid_alive(service) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not pid_alive(service), "the service outlived the launcher that started it"
    finally:
        launcher.kill()
        launcher.wait(10)
        for stream in (launcher.stdin, launcher.stdout):
            if stream is not None:
                stream.close()


def _records_status(port: int, timeout: float = 60.0) -> int:
    """Return what the service on `port` answers a GET of its records without a token (401
    once it is up), waiting until it answers."""
    url = f"http://127.0.0.1:{port}/services/{SERVICE_NAME}/api/records"
    deadline = time.monotonic() + timeout
    while True:
        try:
            return requests.get(url, timeout=5).status_code
        except requests.RequestException:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.2)


def _squat(port: int) -> list[str]:
    """Try to bind `port` every way another account would; return the ways that worked."""
    took = []
    for host, option in [
        ("127.0.0.1", socket.SO_REUSEADDR),
        ("127.0.0.1", socket.SO_REUSEPORT),
        ("0.0.0.0", socket.SO_REUSEADDR),
    ]:
        with socket.socket() as squatter:
            squatter.setsockopt(socket.SOL_SOCKET, option, 1)
            try:
                squatter.bind((host, port))
            except OSError:
                continue
            took.append(f"{host} {option}")
    return took


def test_a_killed_service_starts_again_on_the_socket_its_launcher_holds(tmp_path: Path) -> None:
    listener = bind_service_socket()
    port = listener.getsockname()[1]
    environment = service_environment(port, "t" * 64, "http://127.0.0.1:9/hub/api")
    said: list[str] = []
    kept = KeptService(
        lambda: start_service(sys.executable, tmp_path / "progress.sqlite", listener, environment),
        "The progress service",
        log=said.append,
    )
    try:
        assert _records_status(port) == 401
        first = kept.process.pid
        os.kill(first, signal.SIGKILL)  # as a crash would
        assert _squat(port) == [], "the dead service's port was free to bind"
        assert wait_until(lambda: kept.process.pid != first, 15.0), said
        assert _records_status(port) == 401, "the restarted service does not answer"
        assert [line for line in said if "killed by SIGKILL" in line], said
        assert "started again on the same socket" in said[0], said
    finally:
        kept.stop()
        listener.close()
    assert kept.process.returncode == 0, "SIGTERM stops it cleanly, and it stays stopped"


def test_a_service_that_dies_at_once_is_started_at_a_bounded_rate() -> None:
    starts: list[float] = []

    def start() -> subprocess.Popen[bytes]:
        starts.append(time.monotonic())
        return subprocess.Popen([sys.executable, "-c", "raise SystemExit(3)"])

    said: list[str] = []
    kept = KeptService(start, "A broken service", log=said.append, burst=3, window_s=3.0)
    try:
        assert wait_until(lambda: len(starts) >= 4, 20.0), said
    finally:
        kept.stop()
    assert starts[2] - starts[0] < 3.0, "the first restarts come at once"
    assert starts[3] - starts[0] >= 3.0 - 0.1, f"a 4th start within the window: {starts}"
    paused = [line for line in said if "stopped 3 times in 3 s (exit status 3)" in line]
    assert paused and "starts again in" in paused[0], said


def _uid(pid: int) -> int:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("Uid:"):
            return int(line.split()[1])  # the real uid (effective and saved follow)
    raise AssertionError(f"no Uid line for pid {pid}")


@pytest.fixture
def open_parent() -> Iterator[Path]:
    """A folder every account may enter (as /var/lib is), for the hub's state."""
    folder = Path(tempfile.mkdtemp(prefix="ros2-course-progress-test-"))
    folder.chmod(0o711)
    try:
        yield folder
    finally:
        shutil.rmtree(folder, ignore_errors=True)


@ROOT_ONLY
@pytest.mark.slow
@pytest.mark.learners_env
@pytest.mark.timeout(1800)
def test_the_service_runs_as_its_own_account_on_the_socket_handed_over(
    open_parent: Path,
) -> None:
    # the service account runs the learners' environment, as under the hub (this clone's
    # .venv need not be open to other accounts); built once per clone, shared by hub tests
    build = start_prebuild()
    assert build.wait(timeout=1500) == 0, build.text()[-4000:]
    python = str(hub_environment() / "course" / ".venv" / "bin" / "python")
    account = ensure_system_account(SERVICE_ACCOUNT)
    assert account.pw_uid != 0 and account.pw_shell.endswith(("nologin", "false"))
    (open_parent / "state").mkdir(mode=0o700)
    folder = records_folder(open_parent / "state", account)
    listener = bind_service_socket()
    port = listener.getsockname()[1]
    environment = service_environment(port, "t" * 64, "http://127.0.0.1:9/hub/api")
    service = start_service(python, folder / "progress.sqlite", listener, environment,
                            account)  # fmt: skip
    listener.close()  # the service holds the only copy now
    try:
        url = f"http://127.0.0.1:{port}/services/{SERVICE_NAME}/api/records"
        deadline, status = time.monotonic() + 60, 0
        while status != 401 and time.monotonic() < deadline and service.poll() is None:
            try:  # the port takes connections at once; the service answers once it is up
                status = requests.get(url, timeout=10).status_code
            except requests.Timeout:
                continue
            except requests.ConnectionError:
                raise AssertionError("the handed-over socket refused a connection") from None
            time.sleep(0.2)
        assert status == 401, f"the service answered {status} (exit {service.poll()})"
        assert _uid(service.pid) == account.pw_uid != 0
        assert (folder / "progress.sqlite").stat().st_uid == account.pw_uid
        assert folder.stat().st_mode & 0o077 == 0, "the records are the service's alone"
        nobody = pwd.getpwnam("nobody")
        assert nobody.pw_uid != account.pw_uid
    finally:
        stop_service(service)
    assert service.returncode == 0, "SIGTERM stops it cleanly"
