"""Send a lesson's self-check to the class's progress page, when the lesson runs on a hub.

On a hub, a learner's server has COURSE_PROGRESS_URL (the progress service), and JupyterHub's
JUPYTERHUB_API_TOKEN and JUPYTERHUB_USER; its kernels inherit them. The record goes in a
daemon thread with a short timeout, so the learner's cell never waits on it and never sees an
exception; a failure is said in one line, once per kernel. Outside a hub nothing is sent.
Standard library only: this runs in the learner's kernel.
"""

from __future__ import annotations

import json
import os
import sys
import threading
import urllib.error
import urllib.request
from collections.abc import Callable, Mapping, Sequence
from typing import Protocol

from .record import PROGRESS_URL_ENV, Record, record_body

__all__ = ["TIMEOUT_S", "report_attempt", "report_progress", "send_record"]

TIMEOUT_S = 2.0
_warned = threading.Event()  # one line per kernel, not one per self-check


class _Check(Protocol):
    what: str
    passed: bool


class SelfCheckResult(Protocol):
    """What the client needs of a lesson's self-check (course_lib.lessons.report.SelfCheck)."""

    lesson: int
    passed: bool
    checks: Sequence[_Check]


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


def send_record(url: str, token: str, record: Record, timeout: float = TIMEOUT_S) -> None:
    """POST `record` to the service at `url` with `token`; raise what went wrong."""
    request = urllib.request.Request(
        url.rstrip("/") + "/api/records",
        data=record_body(record),
        method="POST",
        headers={"Authorization": f"token {token}", "Content-Type": "application/json"},
    )
    with urllib.request.urlopen(request, timeout=timeout) as response:
        response.read()


def _send_quietly(url: str, token: str, record: Record) -> None:
    try:
        send_record(url, token, record)
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
    try:
        thread = threading.Thread(
            target=_send_quietly,
            args=(url, token, make(user)),
            name="course-progress-report",
            daemon=True,
        )
        thread.start()
    except Exception as error:  # e.g. no thread left: the self-check still shows
        _send_failed(error)
        return None
    return thread
