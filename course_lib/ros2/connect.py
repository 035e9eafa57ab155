"""The terminal side of the `ros2` daemon: find or start it, send argv, relay its output.

Nothing here imports rclpy, so a terminal command costs a Python start and one round trip.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import socket
import subprocess
import sys
import time
from collections.abc import Mapping
from pathlib import Path
from typing import TextIO

from ..paths import runtime_dir
from ..processes import OWNER_ENV, owner_tag

__all__ = ["DaemonUnavailable", "daemon_socket", "request", "spawn_detached"]

START_TIMEOUT_S = 10.0
IDLE_ENV = "COURSE_ROS2_DAEMON_IDLE_S"
DETACHED_IDLE_S = "600"


class DaemonUnavailable(Exception):
    """No daemon answers on this domain's socket (and none could be started)."""


def daemon_socket(domain_id: int | str) -> Path:
    """Return the socket path of the daemon serving `domain_id`."""
    return runtime_dir() / f"ros2-daemon-{domain_id}.sock"


def _connect(path: Path) -> socket.socket:
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        sock.connect(str(path))
    except OSError:
        sock.close()
        raise DaemonUnavailable(str(path)) from None
    return sock


def daemon_argv() -> list[str]:
    """Return the command line that starts a daemon with this interpreter."""
    return [sys.executable, "-m", "course_lib.ros2.daemon"]


def spawn_detached(env: Mapping[str, str]) -> None:
    """Start a daemon that outlives this command, owned by the shell that ran it.

    It exits after DETACHED_IDLE_S idle seconds; once its shell is gone, the next course
    session reaps it, and `make stop` lists and stops it like every course process.
    """
    child_env = {**env, IDLE_ENV: env.get(IDLE_ENV, DETACHED_IDLE_S)}
    child_env[OWNER_ENV] = owner_tag(os.getppid())
    repo_root = str(Path(__file__).resolve().parents[2])
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


def connect_or_start(domain_id: str, env: Mapping[str, str]) -> socket.socket:
    """Return a connection to this domain's daemon, starting one if none answers."""
    path = daemon_socket(domain_id)
    with contextlib.suppress(DaemonUnavailable):
        return _connect(path)
    spawn_detached(env)
    deadline = time.monotonic() + START_TIMEOUT_S
    while time.monotonic() < deadline:
        with contextlib.suppress(DaemonUnavailable):
            return _connect(path)
        time.sleep(0.02)
    raise DaemonUnavailable(str(path))


def request(
    sock: socket.socket, argv: list[str], *, cwd: str, stdout: TextIO, stderr: TextIO
) -> int:
    """Send one command, copy its output as it comes, and return its exit code."""
    width = shutil.get_terminal_size().columns
    payload = {"argv": argv, "cwd": cwd, "width": width}
    sock.sendall(json.dumps(payload).encode() + b"\n")
    reader = sock.makefile("r", encoding="utf-8")
    try:
        for line in reader:
            frame = json.loads(line)
            if "exit" in frame:
                return int(frame["exit"])
            stream = stdout if "o" in frame else stderr
            stream.write(frame.get("o", frame.get("e", "")))
            stream.flush()
    finally:
        reader.close()
        sock.close()
    raise DaemonUnavailable("the daemon closed the connection")
