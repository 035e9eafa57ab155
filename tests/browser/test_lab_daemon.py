"""A `ros2` daemon started in a lab's terminal belongs to the lab: it outlives the terminal and
dies with the lab, even a SIGKILLed one (issue 10). The terminal is driven through the lab
server's own terminal API, as the JupyterLab page does."""

from __future__ import annotations

import asyncio
import json
import os
import re
import shutil
import signal
import urllib.request
from collections.abc import Iterator

import pytest
from lab_server import ARTIFACTS, LabServer
from lab_terminal import RestTerminal, lab_daemon

from course_lib.core.host.procfs import environ as process_environ
from course_lib.core.host.procfs import pid_alive
from course_lib.core.waiting import wait_until
from course_lib.processes.orphans import owner_tag
from course_lib.ros2.node.connect import daemon_pids, daemon_socket

pytestmark = [pytest.mark.ros, pytest.mark.slow]


class LabTerminal:
    """One terminal of the lab, typed into over its websocket."""

    def __init__(self, lab: LabServer) -> None:
        from tornado.websocket import websocket_connect

        self.lab = lab
        request = urllib.request.Request(
            f"{lab.base_url}/api/terminals?token={lab.token}", method="POST"
        )
        with urllib.request.urlopen(request, timeout=30) as reply:
            self.name = json.loads(reply.read())["name"]
        self.loop = asyncio.new_event_loop()
        asyncio.set_event_loop(self.loop)  # tornado binds the connection to the current loop
        url = f"ws://127.0.0.1:{lab.port}/terminals/websocket/{self.name}?token={lab.token}"
        self.ws = self.loop.run_until_complete(websocket_connect(url))
        self.output = ""

    def run(self, command: str, expect: str, timeout: float = 60.0) -> re.Match[str]:
        """Type `command`; return the match of regex `expect` in what the terminal printed."""
        start = len(self.output)
        self.ws.write_message(json.dumps(["stdin", command + "\r"]))
        deadline = self.loop.time() + timeout
        while not re.search(expect, self.output[start:]):
            remaining = deadline - self.loop.time()
            assert remaining > 0, f"no {expect!r} after `{command}`:\n{self.output[start:]}"
            message = self.loop.run_until_complete(self._read(remaining))
            assert message is not None, f"the terminal closed:\n{self.output[start:]}"
            kind, *rest = json.loads(message)
            if kind == "stdout":
                self.output += rest[0]
        return re.search(expect, self.output[start:])  # type: ignore[return-value]

    async def _read(self, timeout: float) -> str | None:
        return await asyncio.wait_for(self.ws.read_message(), timeout)

    def close(self) -> None:
        """End the terminal and its shell, as closing its tab for good does."""
        self.ws.close()
        request = urllib.request.Request(
            f"{self.lab.base_url}/api/terminals/{self.name}?token={self.lab.token}",
            method="DELETE",
        )
        urllib.request.urlopen(request, timeout=30).close()
        asyncio.set_event_loop(None)
        self.loop.close()


@pytest.fixture
def lab() -> Iterator[LabServer]:
    folder = ARTIFACTS / "lab-daemon"
    shutil.rmtree(folder, ignore_errors=True)
    server = LabServer([], folder)
    try:
        yield server
    finally:
        server.stop()


def test_a_lab_runs_no_daemon_until_its_first_terminal_opens(lab: LabServer) -> None:
    """A learner who only reads and runs notebooks pays for no daemon (issue 66); the first
    terminal starts it as the lab's child, and its first command finds it warm."""
    domain = str(lab.domain_id)
    kernel = json.loads(_post(lab, "/api/kernels"))  # a notebook open: still no daemon
    assert not wait_until(lambda: daemon_pids(domain), 3.0), "the lab started a daemon"
    terminal = RestTerminal(lab.base_url, lab.token)
    daemon = lab_daemon(lab.process.pid)
    assert daemon_pids(domain) == [daemon]
    assert process_environ(daemon)["COURSE_LAB"] == "1"  # it journals the lab's parameters
    terminal.run("ros2 daemon status", "The daemon is running")
    second = RestTerminal(lab.base_url, lab.token)  # a second terminal: still one daemon
    second.run("ros2 node list; echo listed-$?", r"listed-0")
    assert daemon_pids(domain) == [daemon]
    os.kill(daemon, signal.SIGKILL)  # killed (the chaos walk's fault): the next terminal's
    assert wait_until(lambda: not pid_alive(daemon), 5)
    third = RestTerminal(lab.base_url, lab.token)
    daemon = lab_daemon(lab.process.pid)  # ... is the lab's child again, not a stray one
    assert daemon_pids(domain) == [daemon]
    for opened in (third, second, terminal):
        opened.close()
    _post(lab, f"/api/kernels/{kernel['id']}", method="DELETE")
    lab.process.send_signal(signal.SIGTERM)
    assert wait_until(lambda: not pid_alive(daemon), 15), "the daemon outlived its lab"


def _post(lab: LabServer, path: str, method: str = "POST") -> str:
    request = urllib.request.Request(f"{lab.base_url}{path}?token={lab.token}", method=method)
    if method == "POST":
        request.data = b"{}"
    with urllib.request.urlopen(request, timeout=60) as reply:
        return reply.read().decode()


def test_terminal_daemon_outlives_its_terminal_and_dies_with_the_lab(lab: LabServer) -> None:
    domain = str(lab.domain_id)
    terminal = LabTerminal(lab)
    shell = int(terminal.run('echo "shell:$$:"', r"shell:(\d+):")[1])
    lab_daemon(lab.process.pid)  # the lab's own one, which the terminal asked for
    terminal.run("ros2 daemon stop", "The daemon has been stopped")
    terminal.run("ros2 daemon start", "The daemon has been started")
    (daemon,) = daemon_pids(domain)
    assert process_environ(daemon)["COURSE_OWNER"] == owner_tag(lab.process.pid)
    terminal.close()
    assert wait_until(lambda: not pid_alive(shell), 10)
    assert not wait_until(lambda: not pid_alive(daemon), 2.0)  # still serving the lab
    lab.process.send_signal(signal.SIGKILL)  # the lab dies without a word
    assert wait_until(lambda: not pid_alive(daemon), 5), "the daemon outlived its lab"
    # It stopped itself (a daemon killed by someone else leaves its socket behind).
    assert not os.path.exists(daemon_socket(domain))
