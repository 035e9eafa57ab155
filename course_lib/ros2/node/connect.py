"""The terminal side of the `ros2` daemon: find or start it, send argv, relay its output.

Nothing here imports rclpy, so a terminal command costs a Python start and one round trip.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import socket
import subprocess
import sys
import time
from collections.abc import Iterator, Mapping
from pathlib import Path

from ...core.host import procfs
from ...core.waiting import wait_until
from ...processes.orphans import CLONE_ENV, OWNER_ENV, owner_tag
from .participants import of_domain_here
from .wire import (
    DaemonUnavailable,
    connect,
    daemon_lock,
    daemon_socket,
    daemon_start_lock,
    request,
)

__all__ = [
    "DaemonUnavailable",
    "daemon_lock",
    "daemon_pids",
    "daemon_running",
    "daemon_socket",
    "request",
    "spawn_detached",
    "start_detached",
    "start_turn",
    "stop_daemon",
]

START_TIMEOUT_S = 10.0
STOP_TIMEOUT_S = 10.0
IDLE_ENV = "COURSE_ROS2_DAEMON_IDLE_S"
DETACHED_IDLE_S = "600"
SHUTDOWN = "shutdown"


def daemon_argv() -> list[str]:
    """Return the command line that starts a daemon with this interpreter."""
    return [sys.executable, "-m", "course_lib.ros2.command.daemon"]


def _owner_pid() -> int:
    """Return who owns a daemon this command starts: its lab, else the terminal's shell.

    The shell is the session leader (so `time ros2 ...` or a script in that terminal does
    not own it), or the parent process when this command leads its own session.
    """
    from ...processes.lab_markers import owning_lab

    lab = owning_lab(os.getpid())
    if lab is not None:
        return lab
    leader = os.getsid(0)
    return leader if leader not in (0, os.getpid()) and procfs.pid_alive(leader) else os.getppid()


def spawn_detached(env: Mapping[str, str]) -> None:
    """Start a daemon that outlives this command, owned by its lab or else by its shell.

    It exits when its owner is gone (a lab's daemon dies with the lab, whichever terminal
    or cell started it), after DETACHED_IDLE_S idle seconds, or on `ros2 daemon stop`;
    `make stop` lists and stops it like every course process.
    """
    child_env = {**env, IDLE_ENV: env.get(IDLE_ENV, DETACHED_IDLE_S)}
    child_env[OWNER_ENV] = owner_tag(_owner_pid())
    repo_root = str(Path(__file__).resolve().parents[3])
    child_env[CLONE_ENV] = repo_root
    child_env["PYTHONPATH"] = os.pathsep.join(
        p for p in (repo_root, child_env.get("PYTHONPATH", "")) if p
    )
    subprocess.Popen(
        daemon_argv(),
        env=child_env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
        close_fds=True,
        cwd="/",
    )


def _waitconnect(path: str, timeout: float) -> socket.socket:
    deadline = time.monotonic() + timeout
    while True:
        try:
            return connect(path)
        except DaemonUnavailable:
            if time.monotonic() >= deadline:
                raise
        time.sleep(0.01)


def _start_once(env: Mapping[str, str]) -> tuple[socket.socket, bool]:
    """Connect to env's domain's daemon, starting it first unless one answers; return the
    connection and whether this call started the daemon.

    Commands that start at the same moment (first calls in several terminals) take turns
    here, so only the first starts a daemon: a daemon started for nothing still took its
    second to start, and one that lost the race while the winner was being stopped became a
    second daemon nobody asked for.
    """
    path = daemon_socket(env["ROS_DOMAIN_ID"])
    with start_turn(env["ROS_DOMAIN_ID"]):
        with contextlib.suppress(DaemonUnavailable):
            return connect(path), False
        spawn_detached(env)
        return _waitconnect(path, START_TIMEOUT_S), True


@contextlib.contextmanager
def start_turn(domain_id: int | str) -> Iterator[None]:
    """Hold the domain's start lock: whatever starts or stops its daemon (a command, a lab as
    its terminal opens, `ros2 daemon stop`) takes turns, at most START_TIMEOUT_S each."""
    fd = os.open(daemon_start_lock(domain_id), os.O_RDWR | os.O_CREAT, 0o600)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # releases the lock


def connect_or_start(domain_id: str, env: Mapping[str, str]) -> socket.socket:
    """Return a connection to this domain's daemon, starting one if none answers."""
    with contextlib.suppress(DaemonUnavailable):
        return connect(daemon_socket(domain_id))
    return _start_once({**env, "ROS_DOMAIN_ID": domain_id})[0]


def daemon_running(domain_id: int | str) -> bool:
    """Return whether a daemon answers for `domain_id`."""
    try:
        connect(daemon_socket(domain_id)).close()
    except DaemonUnavailable:
        return False
    return True


def start_detached(env: Mapping[str, str]) -> bool:
    """Start env's domain's daemon and wait until it answers; False if one was running."""
    sock, started = _start_once(env)
    sock.close()
    return started


def stop_daemon(domain_id: int | str, *, timeout: float = STOP_TIMEOUT_S) -> bool:
    """Stop the domain's daemon and wait until its process is gone; False if none ran.

    Raises TimeoutError when it is still there after `timeout` seconds. A daemon being
    started (by a command, or by a lab as its terminal opens) is waited for, then stopped.
    """
    try:
        with start_turn(domain_id):
            sock = connect(daemon_socket(domain_id))
    except DaemonUnavailable:
        return False
    with sock, sock.makefile("r", encoding="utf-8") as reader:
        sock.sendall(json.dumps({"control": SHUTDOWN}).encode() + b"\n")
        reply = json.loads(reader.readline() or "{}")
    pid = int(reply.get("pid", 0))
    if pid:
        wait_until(
            lambda: not procfs.pid_alive(pid),
            timeout,
            interval=0.01,
            message="Timed out waiting for daemon to shutdown",
        )
    return True


def daemon_pids(domain_id: int | str) -> list[int]:
    """Return the pids of the daemon processes serving `domain_id` on this network (whoever
    owns them): a network namespace of its own has its own domains, so the same number there
    is another domain (a walled class hub numbers its learners' domains from 1 too)."""
    network = procfs.network_namespace()
    return [
        pid
        for pid in procfs.pids()
        if "course_lib.ros2.command.daemon" in (procfs.cmdline(pid) or ())
        and of_domain_here(pid, domain_id, network)
    ]
