"""Send a lesson's self-check to the class's progress page, when the lesson runs on a hub.

On a hub, a learner's server has COURSE_PROGRESS_URL (the progress service), and JupyterHub's
JUPYTERHUB_API_TOKEN and JUPYTERHUB_USER; its kernels inherit them. The record goes in a
daemon thread with a short timeout, so the learner's cell never waits on it and never sees an
exception; a failure is said in one line, once per kernel. Outside a hub nothing is sent.
Standard library only: this runs in the learner's kernel.

The token opens the learner's lab, so it goes to a port on this host (the class hub's
127.0.0.1:<port>) only once the connection is made and the socket that took it is the hub's
(COURSE_PROGRESS_HOLDER_UID, root by default): a port another account bound, the service's
dead or not, gets nothing.
"""

from __future__ import annotations

import functools
import http.client
import ipaddress
import json
import os
import sys
import threading
import urllib.error
import urllib.request
from collections.abc import Callable, Mapping, Sequence
from typing import Any, Protocol
from urllib.parse import urlsplit

from ...core.host.ports import held_only_by
from .record import PROGRESS_HOLDER_ENV, PROGRESS_URL_ENV, Record, record_body

__all__ = [
    "TIMEOUT_S",
    "UntrustedPortError",
    "report_attempt",
    "report_progress",
    "send_record",
]

TIMEOUT_S = 2.0
ROOT = 0  # the class hub's launcher, which holds the service's port
_warned = threading.Event()  # one line per kernel, not one per self-check


class _Check(Protocol):
    @property
    def what(self) -> str: ...

    @property
    def passed(self) -> bool: ...


class SelfCheckResult(Protocol):
    """What the client needs of a lesson's self-check (course_lib.lessons.report.SelfCheck)."""

    @property
    def lesson(self) -> int: ...

    @property
    def passed(self) -> bool: ...

    @property
    def checks(self) -> Sequence[_Check]: ...


def _record(check: SelfCheckResult, user: str) -> Record:
    failed = next((c.what for c in check.checks if not c.passed), "")
    return Record(user=user, lesson=check.lesson, passed=check.passed, failed=failed)


def _reason(error: Exception) -> str:
    if isinstance(error, urllib.error.HTTPError):
        try:
            said = json.loads(error.read().decode("utf-8")).get("error", "")
        except (ValueError, OSError, AttributeError):
            said = ""
        return f"the service answered {error.code}" + (f" ({said})" if said else "")
    if isinstance(error, urllib.error.URLError):
        return f"cannot reach it ({error.reason})"
    return str(error) or type(error).__name__


class UntrustedPortError(ConnectionError):
    """The port on this host that a record was to go to is another account's."""


class _HeldConnection(http.client.HTTPConnection):
    """An HTTP connection that sends nothing unless account `holder` holds the port."""

    def __init__(self, host: str, *, holder: int, **kwargs: Any) -> None:
        super().__init__(host, **kwargs)
        self.holder = holder

    def connect(self) -> None:
        super().connect()
        host, port = self.sock.getpeername()[:2]
        if not held_only_by(host, port, self.holder):  # checked once connected: no race
            self.close()
            raise UntrustedPortError(
                f"{host}:{port} is held by another account than the hub's, uid "
                f"{self.holder}: nothing was sent"
            )


class _HeldHandler(urllib.request.HTTPHandler):
    def __init__(self, holder: int) -> None:
        super().__init__()
        self.holder = holder

    def http_open(self, req: urllib.request.Request) -> http.client.HTTPResponse:
        return self.do_open(functools.partial(_HeldConnection, holder=self.holder), req)


class _NoRedirect(urllib.request.HTTPRedirectHandler):
    def redirect_request(self, *args: Any, **kwargs: Any) -> None:
        return None  # the records API never redirects: a 3xx is refused, the token kept


def _on_this_host(url: str) -> bool:
    host = urlsplit(url).hostname or ""
    try:
        return host == "localhost" or ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False  # a name: another machine (a Kubernetes service), its network's care


def send_record(
    url: str, token: str, record: Record, timeout: float = TIMEOUT_S, *, holder: int = ROOT
) -> None:
    """POST `record` to the service at `url` with `token`; raise what went wrong. On this
    host, only to a port whose listening socket account `holder` made (UntrustedPortError)."""
    request = urllib.request.Request(
        url.rstrip("/") + "/api/records",
        data=record_body(record),
        method="POST",
        headers={"Authorization": f"token {token}", "Content-Type": "application/json"},
    )
    if _on_this_host(url):
        handlers = (urllib.request.ProxyHandler({}), _HeldHandler(holder), _NoRedirect())
        opener = urllib.request.build_opener(*handlers)
    else:
        opener = urllib.request.build_opener()
    with opener.open(request, timeout=timeout) as response:
        response.read()


def _send_quietly(url: str, token: str, record: Record, holder: int) -> None:
    try:
        send_record(url, token, record, holder=holder)
    except Exception as error:  # never into the learner's cell: one line, once
        _send_failed(error)


def _send_failed(error: Exception) -> None:
    if not _warned.is_set():
        _warned.set()
        print(
            f"(The class's progress page did not get this self-check: {_reason(error)}. "
            "Your lesson is not affected.)",
            file=sys.stderr,
        )


def report_progress(
    check: SelfCheckResult, environ: Mapping[str, str] | None = None
) -> threading.Thread | None:
    """Send `check` to the progress service in a daemon thread; None outside a hub.

    Returns the thread (a test may join it); the lesson does not wait for it.
    """
    return _post(lambda user: _record(check, user), environ)


def report_attempt(
    lesson: int,
    exercise: str,
    attempt: int,
    passed: bool,
    environ: Mapping[str, str] | None = None,
) -> threading.Thread | None:
    """Send one exercise attempt to the progress service, as `report_progress` does."""
    return _post(lambda user: Record(user, lesson, passed, "", exercise, attempt), environ)


def _post(
    make: Callable[[str], Record], environ: Mapping[str, str] | None
) -> threading.Thread | None:
    env = os.environ if environ is None else environ
    url, token = env.get(PROGRESS_URL_ENV), env.get("JUPYTERHUB_API_TOKEN")
    user = env.get("JUPYTERHUB_USER")
    if not (url and token and user):
        return None
    named = env.get(PROGRESS_HOLDER_ENV, "")
    holder = int(named) if named.isdigit() else ROOT
    try:
        thread = threading.Thread(
            target=_send_quietly,
            args=(url, token, make(user), holder),
            name="course-progress-report",
            daemon=True,
        )
        thread.start()
    except Exception as error:  # e.g. no thread left: the self-check still shows
        _send_failed(error)
        return None
    return thread
