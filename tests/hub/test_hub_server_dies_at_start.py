"""A learner's server that dies as it starts fails their spawn at once (real hub).

JupyterHub only asks whether a started server answers: a server that had died (an account
whose home it could not enter, seen at stop 46) left the learner on "Your server is starting
up" for the whole http_timeout, 120 s, before "didn't respond".
"""

from __future__ import annotations

import json
import os
import pwd
import time
from pathlib import Path

import pytest
import requests
from class_hub import ClassHub
from hub_sign_in import sign_in

from course_lib.hub.guard.wall import wall_problem
from course_lib.hub.launcher import NO_WALL_ENV

pytestmark = [pytest.mark.slow, pytest.mark.learners_env]

LEARNER, ADMIN = "r2pw-dee", "r2pw-dad"
REPORTED_WITHIN_S = 30.0  # the server's own start and death take a few seconds
ASK_AGAIN_FOR_S = 60.0  # how long a "not starting" answer is asked again (a clean-up's time)


def _last_progress_event(session: requests.Session, hub: ClassHub, name: str) -> dict:
    """Follow the spawn's progress as the "starting" page does; return its last event.

    A server that died is first stopped and cleaned up (the post-stop hook stops what it
    left); only then is the spawn marked failed. In between, the hub answers the progress
    stream with 400 "not starting" and sends a browser its "stopping" page, which reloads
    until the failure shows: ask again, as that reload does (seen on a slow host, and made
    certain by a post-stop hook that sleeps)."""
    url = f"{hub.url}/hub/api/users/{name}/server/progress"
    deadline = time.monotonic() + ASK_AGAIN_FOR_S
    while True:
        with session.get(url, stream=True, timeout=180) as events:
            stopping = events.status_code == 400 and "is not starting" in events.text
            if stopping and time.monotonic() < deadline:
                time.sleep(0.5)
                continue
            assert events.status_code == 200, events.text
            event: dict = {}
            for line in events.iter_lines():
                if line.startswith(b"data:"):
                    event = json.loads(line[len(b"data:") :])
                    if event.get("failed") or event.get("ready"):
                        break
            return event


@pytest.mark.parametrize("wall", [True, False], ids=["own-network", "host-network"])
def test_a_server_that_dies_as_it_starts_fails_the_spawn_at_once(
    tmp_path_factory: pytest.TempPathFactory, wall: bool
) -> None:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    if wall and wall_problem():
        pytest.skip(f"no network namespace here: {wall_problem()}")
    # behind the wall the server listens on a Unix socket; without it, on a port
    hub = ClassHub(
        (LEARNER,), (ADMIN,), tmp_path_factory.mktemp("dying-server-hub"),
        env_extra={} if wall else {NO_WALL_ENV: "1"},
    )  # fmt: skip
    account = pwd.getpwnam(LEARNER)
    home = Path(account.pw_dir)
    try:
        assert ("The domain wall is on" in hub.log()) == wall, hub.log()[-2000:]
        os.chown(home, 0, 0)  # a home the learner can enter but not write: the server dies
        began = time.monotonic()
        session, _page = sign_in(hub.url, LEARNER, hub.passwords[LEARNER], timeout=180)
        event = _last_progress_event(session, hub, LEARNER)
        reported = time.monotonic() - began
        assert event.get("failed"), event
        assert f"{LEARNER}'s server stopped as it started" in event["message"], event
        assert reported < REPORTED_WITHIN_S, f"reported after {reported:.0f} s: {event}"
    finally:
        os.chown(home, account.pw_uid, account.pw_gid)
        hub.stop()
