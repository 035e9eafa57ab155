"""A learner's server that dies as it starts fails their spawn at once (real hub).

JupyterHub only asks whether a started server answers: a server that had died (an account
whose home it could not enter, seen at stop 46) left the learner on "Your server is starting
up" for the whole http_timeout, 120 s, before "didn't respond".
"""

from __future__ import annotations

import json
import os
import pwd
import re
import time
from pathlib import Path

import pytest
import requests
from class_hub import ClassHub

pytestmark = [pytest.mark.slow]

LEARNER, ADMIN = "r2pw-dee", "r2pw-dad"
REPORTED_WITHIN_S = 30.0  # the server's own start and death take a few seconds


def _log_in(hub: ClassHub, name: str) -> requests.Session:
    """Sign in through the login form, as a browser does (the hub then starts the server)."""
    session = requests.Session()
    form = session.get(f"{hub.url}/hub/login", timeout=30)
    xsrf = re.search(r'name="_xsrf" value="([^"]+)"', form.text)
    assert xsrf, form.text[:500]
    session.post(
        f"{hub.url}/hub/login",
        data={"username": name, "password": hub.passwords[name], "_xsrf": xsrf.group(1)},
        timeout=180,
    )
    return session


def _last_progress_event(session: requests.Session, hub: ClassHub, name: str) -> dict:
    """Follow the spawn's progress as the "starting" page does; return its last event."""
    url = f"{hub.url}/hub/api/users/{name}/server/progress"
    event: dict = {}
    with session.get(url, stream=True, timeout=180) as events:
        assert events.status_code == 200, events.text
        for line in events.iter_lines():
            if line.startswith(b"data:"):
                event = json.loads(line[len(b"data:") :])
                if event.get("failed") or event.get("ready"):
                    break
    return event


def test_a_server_that_dies_as_it_starts_fails_the_spawn_at_once(
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    hub = ClassHub((LEARNER,), (ADMIN,), tmp_path_factory.mktemp("dying-server-hub"))
    account = pwd.getpwnam(LEARNER)
    home = Path(account.pw_dir)
    try:
        os.chown(home, 0, 0)  # a home the learner can enter but not write: the server dies
        began = time.monotonic()
        session = _log_in(hub, LEARNER)
        event = _last_progress_event(session, hub, LEARNER)
        reported = time.monotonic() - began
        assert event.get("failed"), event
        assert f"{LEARNER}'s server stopped as it started" in event["message"], event
        assert reported < REPORTED_WITHIN_S, f"reported after {reported:.0f} s: {event}"
    finally:
        os.chown(home, account.pw_uid, account.pw_gid)
        hub.stop()
