"""Acting on a real class hub as its accounts: sign in over HTTP, type in a learner's lab
terminal, run a command as another account (no browser: the hub and the lab are real)."""

from __future__ import annotations

import os
import pwd
import re
import subprocess
import time
from pathlib import Path

import requests
from class_hub import ClassHub, server_token
from lab_terminal import RestTerminal

__all__ = ["as_account", "lab_terminal", "server_pid", "sign_in", "tcp_listeners"]


def sign_in(hub: ClassHub, name: str, timeout: float = 180.0) -> requests.Session:
    """Sign `name` in through the hub's login form; return the session once their server
    answers its API through the hub (the hub starts it at sign-in)."""
    session = requests.Session()
    page = session.get(f"{hub.url}/hub/login", timeout=30)
    xsrf = re.search(r'name="_xsrf"\s+value="([^"]+)"', page.text)
    form = {"username": name, "password": hub.passwords[name]}
    if xsrf:
        form["_xsrf"] = xsrf[1]
    session.post(f"{hub.url}/hub/login", data=form, timeout=60)
    deadline = time.monotonic() + timeout
    while True:
        reply = session.get(f"{hub.url}/user/{name}/lab", timeout=60)
        if reply.status_code == 200 and f"/user/{name}/lab" in reply.url:
            return session
        if time.monotonic() > deadline:
            raise AssertionError(
                f"{name}'s server did not answer within {timeout:.0f} s "
                f"({reply.status_code} at {reply.url}):\n{hub.log()[-4000:]}"
            )
        time.sleep(1.0)


def lab_terminal(hub: ClassHub, name: str) -> RestTerminal:
    """Open a terminal in `name`'s lab, through the hub, with their server's own token."""
    return RestTerminal(f"{hub.url}/user/{name}", server_token(name))


def server_pid(name: str) -> int:
    """Return the pid of `name`'s `course_lib hub-lab` (the process the hub started)."""
    uid = pwd.getpwnam(name).pw_uid
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if entry.stat().st_uid != uid:
                continue
            command = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if b"hub-lab" in command:
            return int(entry.name)
    raise AssertionError(f"{name} has no server running")


def environ_of(pid: int) -> dict[str, str]:
    items = Path(f"/proc/{pid}/environ").read_bytes().split(b"\0")
    return dict(item.decode().split("=", 1) for item in items if b"=" in item)


def _socket_inodes(uid: int) -> set[str]:
    """Return the inodes of every socket held by a process of `uid`."""
    found = set()
    for entry in Path("/proc").iterdir():
        try:
            if not entry.name.isdigit() or entry.stat().st_uid != uid:
                continue
            for fd in (entry / "fd").iterdir():
                link = os.readlink(fd)
                if link.startswith("socket:["):
                    found.add(link[8:-1])
        except OSError:
            continue
    return found


def tcp_listeners(pid: int, uid: int) -> set[int]:
    """Return the TCP ports on which processes of `uid` listen, in `pid`'s network."""
    mine = _socket_inodes(uid)
    ports = set()
    for table in ("tcp", "tcp6"):
        lines = Path(f"/proc/{pid}/net/{table}").read_text().splitlines()[1:]
        for line in lines:
            fields = line.split()
            if fields[3] == "0A" and fields[9] in mine:  # LISTEN
                ports.add(int(fields[1].rsplit(":", 1)[1], 16))
    return ports


def as_account(
    name: str,
    argv: list[str],
    env: dict[str, str],
    timeout: float = 60.0,
    *,
    stdin: str | None = None,
) -> subprocess.CompletedProcess[str]:
    """Run `argv` as Unix account `name` on the host (its network, its home), as that account
    would from a shell of its own; `stdin` is what it reads (never on a command line)."""
    account = pwd.getpwnam(name)

    def become() -> None:
        os.setgroups([])
        os.setgid(account.pw_gid)
        os.setuid(account.pw_uid)

    full = {"HOME": account.pw_dir, "USER": name, "PATH": os.defpath, **env}
    return subprocess.run(
        argv, env=full, cwd=account.pw_dir, preexec_fn=become, capture_output=True,
        text=True, timeout=timeout, check=False, input=stdin,
    )  # fmt: skip
