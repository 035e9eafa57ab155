"""The lessons' reporting client: sends on a hub only, never raises, never holds the cell."""

from __future__ import annotations

import http.server
import json
import os
import socket
import threading
import time
from collections.abc import Iterator

import pytest

from course_lib.core.host.ports import free_port
from course_lib.lessons.progress import client as progress_report
from course_lib.lessons.progress.client import TIMEOUT_S, report_progress
from course_lib.lessons.report import SelfCheck, check

CHECK = SelfCheck.of(
    6, [check("first", True), check("second", False, "hint"), check("third", False)]
)


@pytest.fixture(autouse=True)
def _fresh_kernel() -> None:
    progress_report._warned.clear()  # the once-per-kernel line, as in a new kernel


@pytest.fixture
def receiver() -> Iterator[tuple[str, list[tuple[str, dict, bytes]]]]:
    """Yield the URL of a local HTTP server that stores what is posted, and what it got."""
    got: list[tuple[str, dict, bytes]] = []

    class Handler(http.server.BaseHTTPRequestHandler):
        def do_POST(self) -> None:
            body = self.rfile.read(int(self.headers["Content-Length"]))
            got.append((self.path, dict(self.headers), body))
            self.send_response(201)
            self.end_headers()

        def log_message(self, *args: object) -> None:
            pass

    server = http.server.HTTPServer(("127.0.0.1", 0), Handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}/services/course-progress/", got
    server.shutdown()
    server.server_close()


def _env(url: str, holder: int | None = None) -> dict[str, str]:
    """A server's environment on a hub whose launcher is this test (it holds the port)."""
    return {
        "COURSE_PROGRESS_URL": url,
        "COURSE_PROGRESS_HOLDER_UID": str(os.getuid() if holder is None else holder),
        "JUPYTERHUB_API_TOKEN": "t0k",
        "JUPYTERHUB_USER": "alice",
    }


@pytest.mark.parametrize(
    "missing", ["COURSE_PROGRESS_URL", "JUPYTERHUB_API_TOKEN", "JUPYTERHUB_USER"]
)
def test_outside_a_hub_nothing_is_sent(missing: str) -> None:
    env = {k: v for k, v in _env("http://127.0.0.1:9/").items() if k != missing}
    assert report_progress(CHECK, environ=env) is None
    assert report_progress(CHECK, environ={}) is None


def test_the_record_names_the_first_failed_check(receiver) -> None:
    url, got = receiver
    report_progress(CHECK, environ=_env(url)).join(5)
    ((path, headers, body),) = got
    assert path == "/services/course-progress/api/records"
    assert headers["Authorization"] == "token t0k"
    assert json.loads(body) == {"user": "alice", "lesson": 6, "passed": False, "failed": "second"}


def test_a_port_held_by_another_account_gets_no_token(
    receiver, capsys: pytest.CaptureFixture[str]
) -> None:
    """The service died and another account bound its port: the record and the token stay."""
    url, got = receiver
    someone_else = os.getuid() + 1  # the receiver's socket is this test's
    report_progress(CHECK, environ=_env(url, holder=someone_else)).join(5)
    assert got == [], "the token went to a port the hub does not hold"
    said = capsys.readouterr().err
    assert f"is held by another account than the hub's, uid {someone_else}" in said, said
    assert said.count("\n") == 1 and "nothing was sent" in said


def test_an_unreachable_service_is_said_once(capsys: pytest.CaptureFixture[str]) -> None:
    url = f"http://127.0.0.1:{free_port()}/services/course-progress/"  # nobody listens there
    for _ in range(2):
        report_progress(CHECK, environ=_env(url)).join(5)
    said = capsys.readouterr()
    assert said.out == ""
    assert said.err.count("\n") == 1 and "did not get this self-check" in said.err, said.err


def test_a_silent_service_never_holds_the_cell(capsys: pytest.CaptureFixture[str]) -> None:
    with socket.socket() as silent:  # listens, never answers
        silent.bind(("127.0.0.1", 0))
        silent.listen(1)
        url = f"http://127.0.0.1:{silent.getsockname()[1]}/services/course-progress/"
        started = time.monotonic()
        thread = report_progress(CHECK, environ=_env(url))
        # well under the request's timeout (a busy host can take a while to start a thread)
        assert time.monotonic() - started < TIMEOUT_S / 2, "the cell waited for the service"
        assert thread is not None and thread.daemon
        thread.join(TIMEOUT_S + 3)
        assert not thread.is_alive(), "the request has no timeout"
    assert "timed out" in capsys.readouterr().err
