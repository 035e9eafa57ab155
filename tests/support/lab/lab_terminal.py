"""A JupyterLab terminal opened and typed into through the server's REST and websocket API.

The same requests the browser's terminal makes (tests/browser/terminal.py drives one from a
page), without a browser: the shell is a real terminado process of the lab.
"""

from __future__ import annotations

import asyncio
import json
import re
import time
import urllib.request
from typing import Any

from tornado.httpclient import HTTPRequest
from tornado.websocket import websocket_connect

__all__ = ["RestTerminal", "close_terminals", "lab_daemon", "open_terminals", "rest"]

CLOSE_WAIT_S = 5.0  # tornado gives a server that long to answer a close
_OPENER = urllib.request.build_opener(urllib.request.ProxyHandler({}))  # the lab is local


def rest(base_url: str, token: str, method: str, path: str, body: Any = None) -> Any:
    """Send one request to the Jupyter server's REST API; return its JSON reply (or None)."""
    request = urllib.request.Request(
        f"{base_url}{path}", method=method, headers={"Authorization": f"token {token}"}
    )
    if method in ("POST", "PUT"):
        request.data = json.dumps(body or {}).encode()
    with _OPENER.open(request, timeout=30) as reply:  # LabServer returns once the lab answers
        body = reply.read()
    return json.loads(body) if body else None


def lab_daemon(lab_pid: int, timeout: float = 30.0) -> int:
    """Return the pid of the lab's ros2 daemon, the lab's child that its first terminal starts
    (course_lib/lab/daemon_keeper.py): wait for it."""
    import psutil

    deadline = time.monotonic() + timeout
    while True:
        for child in psutil.Process(lab_pid).children():
            try:
                if "course_lib.ros2.command.daemon" in child.cmdline():
                    return child.pid
            except psutil.Error:
                continue
        if time.monotonic() > deadline:
            raise AssertionError(f"the lab (pid {lab_pid}) started no ros2 daemon in {timeout} s")
        time.sleep(0.05)


async def _connect(url: str, token: str) -> Any:
    # the token in a header too: a hub's server takes none from the URL (JupyterHub >= 5)
    request = HTTPRequest(url, headers={"Authorization": f"token {token}"})
    return await websocket_connect(request)


async def _write(ws: Any, message: str) -> None:
    await ws.write_message(message)


async def _read(ws: Any, timeout: float) -> str | None:
    return await asyncio.wait_for(ws.read_message(), timeout)


class RestTerminal:
    """One terminal of a running JupyterLab, as the learner opens it from the launcher."""

    def __init__(self, base_url: str, token: str) -> None:
        self.base_url, self.token = base_url, token
        self.name = rest(base_url, token, "POST", "/api/terminals")["name"]
        self.output = ""
        self._loop = asyncio.new_event_loop()
        url = f"{base_url.replace('http', 'ws', 1)}/terminals/websocket/{self.name}"
        self._ws = self._loop.run_until_complete(_connect(f"{url}?token={token}", token))
        _OPEN.add(self)
        self.shell_pid = int(self.run("echo shell-pid=$$", r"shell-pid=(\d+)")[1])

    def run(self, command: str, expect: str, timeout: float = 60.0) -> re.Match[str]:
        """Type `command`; wait until its output matches regex `expect` (not in its echo)."""
        start = len(self.output)
        self._type(command + "\r")
        deadline = time.monotonic() + timeout
        while True:
            typed = self.output[start:].find("\n")  # skip the echoed command line
            found = re.search(expect, self.output[start + typed + 1 :]) if typed >= 0 else None
            if found:
                return found
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise AssertionError(
                    f"the terminal never printed /{expect}/ after `{command}`:\n"
                    f"{self.output[start:][-3000:]}"
                )
            self._receive(remaining)

    def _type(self, text: str) -> None:
        """Send keys on this terminal's own loop (never the thread's current one, which an
        earlier `asyncio.run` in the same test process may have closed)."""
        self._loop.run_until_complete(_write(self._ws, json.dumps(["stdin", text])))

    def _receive(self, timeout: float) -> None:
        try:
            message = self._loop.run_until_complete(_read(self._ws, timeout))
        except asyncio.TimeoutError:
            return
        if message is None:
            raise AssertionError(f"the terminal closed:\n{self.output[-3000:]}")
        kind, *content = json.loads(message)
        if kind == "stdout":
            self.output += content[0]

    def interrupt(self) -> None:
        """Press Ctrl-C, then wait until the shell answers again."""
        self._type("\x03")
        self.run("echo back-$((20 + 22))", r"back-42")

    def close(self) -> None:
        """Close the websocket (the shell keeps running until the server ends it); again: no-op."""
        if self not in _OPEN:
            return
        _OPEN.discard(self)

        async def close() -> None:  # on this terminal's own loop, as every other write
            self._ws.close()
            # until the server's close frame ends the connection (tornado then closes the
            # socket; a loop closed before that leaves it to the garbage collector)
            try:
                while await asyncio.wait_for(self._ws.read_message(), CLOSE_WAIT_S) is not None:
                    pass
            except asyncio.TimeoutError:
                pass

        self._loop.run_until_complete(close())
        self._loop.close()


_OPEN: set[RestTerminal] = set()


def open_terminals() -> set[RestTerminal]:
    """Return the terminals opened and not closed yet."""
    return set(_OPEN)


def close_terminals(terminals: set[RestTerminal]) -> None:
    """Close `terminals` (the suite closes those a test left open, after it)."""
    for terminal in terminals:
        terminal.close()
