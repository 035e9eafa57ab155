"""Shared by the benches that start a real class hub: its start, its accounts, a sign-in.

Not a bench script itself (the leading underscore keeps `python -m bench` from running it).
A hub needs root: it creates the learners' Unix accounts (removed again by `remove_account`).
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import pwd
import re
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import IO

import psutil
import requests

from course_lib.core.paths import REPO_ROOT
from course_lib.hub.launcher import NO_WALL_ENV

__all__ = [
    "ADMIN",
    "Hub",
    "account_pids",
    "default_environment",
    "free_port",
    "remove_account",
    "running_hub",
    "server_token",
    "sign_in",
]

UP = "The class hub is up"
ADMIN = "r2pb-admin"


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def default_environment() -> Path:
    """The learners' environment the tests build (tests/browser/class_hub.py), if any."""
    digest = hashlib.sha1(str(REPO_ROOT).encode()).hexdigest()[:10]
    return Path(tempfile.gettempdir()) / f"ros2-course-hub-env-{digest}"


def account_pids(name: str) -> list[psutil.Process]:
    """Return every process that runs as account `name`."""
    uid = pwd.getpwnam(name).pw_uid
    return [p for p in psutil.process_iter(["uids"]) if p.info["uids"].real == uid]


def remove_account(name: str) -> None:
    """Kill the account's processes and remove it with its home (nothing if it is absent)."""
    with contextlib.suppress(KeyError):
        for process in account_pids(name):
            with contextlib.suppress(psutil.Error):
                process.kill()
        subprocess.run(["userdel", "--remove", name], check=False, capture_output=True)


def server_token(name: str) -> str:
    """Return the hub API token `name`'s server holds (it opens that server's API)."""
    for process in account_pids(name):
        with contextlib.suppress(psutil.Error):
            token = process.environ().get("JUPYTERHUB_API_TOKEN")
            if token:
                return token
    raise RuntimeError(f"no process of {name} holds a hub token")


def sign_in(url: str, name: str, password: str, timeout: float = 240.0) -> float:
    """Sign in; return the seconds until the learner's server answers through the hub."""
    session = requests.Session()
    page = session.get(f"{url}/hub/login", timeout=30)
    xsrf = re.search(r'name="_xsrf"\s+value="([^"]+)"', page.text)
    form = {"username": name, "password": password, **({"_xsrf": xsrf[1]} if xsrf else {})}
    started = time.monotonic()
    session.post(f"{url}/hub/login", data=form, timeout=60)
    while time.monotonic() - started < timeout:
        reply = session.get(f"{url}/user/{name}/lab", timeout=60)
        if reply.status_code == 200 and f"/user/{name}/lab" in reply.url:
            return time.monotonic() - started
        time.sleep(0.2)
    raise RuntimeError(f"{name}'s server did not answer within {timeout:.0f} s")


def _drain(stream: IO[str], log: list[str]) -> None:
    for line in stream:
        log.append(line)
        del log[:-200]


def _running(process: psutil.Process) -> bool:
    """Return True if `process` still runs (a zombie has ended)."""
    try:
        return process.is_running() and process.status() != psutil.STATUS_ZOMBIE
    except psutil.Error:
        return False


def _end_leftovers(tree: list[psutil.Process], log: list[str], patience_s: float = 15.0) -> None:
    """Kill what the stopped hub left of its processes, and say so with the hub's last words
    (two JupyterHubs of 16-learner runs outlived their launcher, idle, for 20 minutes)."""
    deadline = time.monotonic() + patience_s
    while left := [p for p in tree if _running(p)]:
        if time.monotonic() > deadline:
            commands = [" ".join(p.cmdline())[:100] for p in left]
            print(f"the stopped hub left {len(left)} processes: {commands}", file=sys.stderr)
            print("its log ended with:\n" + "".join(log[-40:]), file=sys.stderr)
            for leftover in left:
                with contextlib.suppress(psutil.Error):
                    leftover.kill()
            return
        time.sleep(0.2)


@dataclass
class Hub:
    """A running class hub: its launcher process, address, start time and the passwords."""

    process: subprocess.Popen[str]
    url: str
    port: int
    up_s: float
    walled: bool
    passwords: dict[str, str]


@contextlib.contextmanager
def running_hub(
    learners: list[str], environment: Path, folder: Path, *, wall: bool = True
) -> Iterator[Hub]:
    """Start `python -m course_lib hub` for `learners` (accounts made afresh); stop it after."""
    for name in (*learners, ADMIN):
        remove_account(name)
    port = free_port()
    state = folder / f"state-{'wall' if wall else 'nowall'}"
    config = folder / f"hub-{'wall' if wall else 'nowall'}.yaml"
    config.write_text(
        f"learners: [{', '.join(learners)}]\nadmins: [{ADMIN}]\nport: {port}\n"
        f"environment: {environment}\nstate: {state}\nidle_minutes: 0\n",
        encoding="utf-8",
    )
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "COURSE_"))}
    if not wall:
        env[NO_WALL_ENV] = "1"
    argv = [sys.executable, "-m", "course_lib", "hub", "--config", str(config)]
    started = time.monotonic()
    process = subprocess.Popen(
        argv, cwd=REPO_ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )
    assert process.stdout is not None
    log: list[str] = []
    try:
        for line in process.stdout:
            log.append(line)
            if UP in line:
                break
        else:
            raise RuntimeError("the hub did not start:\n" + "".join(log[-40:]))
        up = time.monotonic() - started
        # the hub logs every request: read on, or a full pipe would stop it mid-bench
        threading.Thread(target=_drain, args=(process.stdout, log), daemon=True).start()
        passwords = dict(
            line.split(" ", 1) for line in (state / "passwords.txt").read_text().splitlines()
        )
        yield Hub(
            process,
            f"http://127.0.0.1:{port}",
            port,
            up,
            any("The domain wall is on" in line for line in log),
            {name: password.strip() for name, password in passwords.items()},
        )
    finally:
        tree: list[psutil.Process] = []
        with contextlib.suppress(psutil.Error):
            tree = psutil.Process(process.pid).children(recursive=True)
        process.send_signal(signal.SIGINT)
        try:
            process.wait(120)
        except subprocess.TimeoutExpired:
            log.append("the launcher did not stop within 120 s of Ctrl-C: killed\n")
            process.kill()
            process.wait()
        _end_leftovers(tree, log)
        for name in (*learners, ADMIN):
            remove_account(name)
