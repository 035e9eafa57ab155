"""The hub's proxy killed outright (issue 62, item 3): the hub starts it again, with every route.

JupyterHub polls the proxy it started every `ConfigurableHTTPProxy.check_running_interval`
seconds (5 by default); a proxy that has exited is started again with the same command (the
course's: tied to the hub, course_lib.hub.guard.tied), after its pid file and its Unix sockets
are removed, and is given back the hub's route, every running server's and every service's.

Both layouts: the proxy on a TCP port (tests/hub/progress_hub.py), and the class hub's, where
it listens on a Unix socket in the state folder behind the launcher's door on the public port
(course_lib/hub/guard/gate.py): a killed proxy leaves that socket's file behind.
"""

from __future__ import annotations

import contextlib
import signal
import socket
import time
from collections.abc import Iterator
from urllib.parse import quote

import psutil
import pytest
import requests
from jupyterhub.proxy import ConfigurableHTTPProxy
from progress_hub import ClassHub

from course_lib.core.waiting import wait_until
from course_lib.hub.guard.gate import BACKLOG, Door, Gate
from course_lib.hub.plan import PROXY_SOCKET
from course_lib.hub.progress import SERVICE_NAME

pytestmark = pytest.mark.slow

CHECK_INTERVAL_S = ConfigurableHTTPProxy.class_traits()["check_running_interval"].default_value
PROXY_START_S = 15.0  # JupyterHub waits that long for a starting proxy's ports
BOUND_S = CHECK_INTERVAL_S + PROXY_START_S
ROUTES = {
    "the hub": "/hub/api/",
    "the progress service": f"/services/{SERVICE_NAME}/api/records",
    "alice's server": "/user/alice/api/status",
}


class SocketHub(ClassHub):
    """A ClassHub laid out as the class hub: its proxy on a Unix socket in the state folder
    (course_lib/hub/hub_config.py), reached through a door on the public port, as the
    launcher's gate opens it."""

    def _config(self) -> str:
        public = "http+unix://" + quote(str(self.root / "state" / PROXY_SOCKET), safe="")
        tcp = ("c.JupyterHub.ip ", "c.JupyterHub.port ")
        lines = [line for line in super()._config().splitlines() if not line.startswith(tcp)]
        return "\n".join([*lines, f"c.JupyterHub.bind_url = {public!r}"]) + "\n"


@contextlib.contextmanager
def running(hub: ClassHub) -> Iterator[ClassHub]:
    """Run `hub` (behind a door on its port, if its proxy is on a socket) with alice's server."""
    with contextlib.ExitStack() as stack:
        if isinstance(hub, SocketHub):
            public = stack.enter_context(
                socket.create_server(("127.0.0.1", hub.port), backlog=BACKLOG)
            )
            door = Door(public, str(hub.root / "state" / PROXY_SOCKET), "the hub's port")
            gate = Gate([door], per_peer=200, log=print)
            gate.start()
            stack.callback(gate.stop)
        stack.callback(hub.close)
        hub.start()
        hub.spawn("alice")
        yield hub


def proxy_process(hub: ClassHub) -> psutil.Process | None:
    """Return the hub's proxy (its child running configurable-http-proxy), if it runs."""
    assert hub.process is not None
    for child in psutil.Process(hub.process.pid).children():
        with contextlib.suppress(psutil.Error):
            alive = child.status() != psutil.STATUS_ZOMBIE
            if alive and "configurable-http-proxy" in " ".join(child.cmdline()):
                return child
    return None


def answers(hub: ClassHub) -> dict[str, str]:
    """Say what each route answers through the proxy (status and the body's start)."""
    seen = {}
    for name, path in ROUTES.items():
        try:
            answer = requests.get(hub.url + path, timeout=2, allow_redirects=False)
            seen[name] = f"{answer.status_code} {answer.text[:30]!r}"
        except requests.RequestException as error:
            seen[name] = type(error).__name__
    return seen


def routed(seen: dict[str, str]) -> bool:
    """Return whether each route reached its own target, not the proxy's or hub's catch-all."""
    return (
        seen["the hub"].startswith("200 ")
        and seen["the progress service"].startswith("401 ")  # its own answer to no token
        and seen["alice's server"].startswith("200 'fake single-user server")
    )


@pytest.mark.parametrize("layout", [ClassHub, SocketHub], ids=["tcp", "unix-socket"])
def test_a_killed_proxy_is_started_again_with_every_route(
    tmp_path_factory: pytest.TempPathFactory, proxy: str, layout: type[ClassHub]
) -> None:
    with running(layout(tmp_path_factory.mktemp("proxy-killed"), proxy)) as hub:
        assert routed(before := answers(hub)), before
        killed = proxy_process(hub)
        assert killed is not None, "the hub runs no configurable-http-proxy"
        killed.send_signal(signal.SIGKILL)
        started = time.monotonic()
        assert wait_until(lambda: not routed(answers(hub)), 5.0), "the proxy answers still"

        again = wait_until(lambda: proxy_process(hub), BOUND_S, interval=0.1)
        assert again is not None and again.pid != killed.pid, (
            f"no new proxy {BOUND_S:.0f} s after the kill; the hub's log:\n{hub.log_tail()}"
        )
        assert wait_until(lambda: routed(answers(hub)), BOUND_S, interval=0.1), (
            f"{BOUND_S:.0f} s after the kill: {answers(hub)}; the hub's log:\n{hub.log_tail()}"
        )
        back_s = time.monotonic() - started
        print(f"\n{layout.__name__}: proxy and routes back {back_s:.1f} s after the kill")
        assert back_s < BOUND_S
        # the launcher's forget_stale_proxy trusts this file after a killed hub
        pid_file = (hub.root / "state" / "proxy.pid").read_text().strip()
        assert pid_file == str(again.pid)
        assert hub.process is not None and hub.process.poll() is None, "the hub stopped"
        # the new proxy is tied to the hub too; alice's stand-in server is not (JupyterHub's
        # simple spawner: the class hub's CourseSpawner ties it), so the test stops it
        children = psutil.Process(hub.process.pid).children(recursive=True)
        hub.process.send_signal(signal.SIGKILL)
        hub.process.wait()
        try:
            assert wait_until(lambda: not _alive(again), 10.0), "the new proxy outlived the hub"
        finally:
            for child in children:
                with contextlib.suppress(psutil.Error):
                    child.kill()


def _alive(process: psutil.Process) -> bool:
    with contextlib.suppress(psutil.Error):
        return process.status() != psutil.STATUS_ZOMBIE
    return False
