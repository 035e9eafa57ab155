"""The `ros2` daemon's socket and its wire format, light enough for the terminal's client.

A command goes as one JSON line (`argv`, `cwd`, `width`, and `env`: the terminal's
environment, for the verbs that read the ament index); the answer comes back as JSON
lines, `{"o": text}` for stdout, `{"e": text}` for stderr, then `{"exit": code}`. This
module imports nothing heavier than `json` and `socket` (no pathlib, no typing: paths are
strings), so the terminal's `ros2` client (course_lib.ros2.command.quick) starts at
interpreter speed.
"""

from __future__ import annotations

import json
import os
import socket

from ...core.runtime_folder import runtime_folder

TYPE_CHECKING = False  # typing is not imported: the terminal's client starts with this module
if TYPE_CHECKING:
    from collections.abc import Mapping
    from typing import TextIO

__all__ = [
    "DaemonUnavailable",
    "connect",
    "daemon_lock",
    "daemon_socket",
    "daemon_start_lock",
    "request",
    "terminal_width",
]


class DaemonUnavailable(Exception):
    """No daemon answers on this domain's socket (and none could be started)."""


def daemon_socket(domain_id: int | str) -> str:
    """Return the socket path of the daemon serving `domain_id`."""
    return os.path.join(runtime_folder(), f"ros2-daemon-{domain_id}.sock")


def daemon_lock(domain_id: int | str) -> str:
    """Return the lock file a daemon of `domain_id` holds for as long as it lives."""
    return os.path.join(runtime_folder(), f"ros2-daemon-{domain_id}.lock")


def daemon_start_lock(domain_id: int | str) -> str:
    """Return the lock file commands take in turns to start a daemon of `domain_id`."""
    return os.path.join(runtime_folder(), f"ros2-daemon-{domain_id}.start")


def connect(path: str) -> socket.socket:
    """Return a connection to the daemon listening at `path` (DaemonUnavailable if none)."""
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        sock.connect(path)
    except OSError:
        sock.close()
        raise DaemonUnavailable(path) from None
    return sock


def terminal_width() -> int:
    """Return the terminal's width as shutil.get_terminal_size() does (COLUMNS first, 80)."""
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(1).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns or 80


def request(
    sock: socket.socket,
    argv: list[str],
    *,
    cwd: str,
    stdout: TextIO,
    stderr: TextIO,
    env: Mapping[str, str] | None = None,
) -> int:
    """Send one command, copy its output as it comes, and return its exit code.

    Raises DaemonUnavailable when the daemon hangs up before it said how the command ended.
    """
    payload: dict[str, object] = {"argv": argv, "cwd": cwd, "width": terminal_width()}
    if env is not None:
        payload["env"] = dict(env)
    try:
        sock.sendall(json.dumps(payload).encode() + b"\n")
        reader = sock.makefile("r", encoding="utf-8")
    except OSError:
        sock.close()
        raise DaemonUnavailable("the daemon closed the connection") from None
    try:
        for line in reader:
            frame = json.loads(line)
            if "exit" in frame:
                return int(frame["exit"])
            if "o" in frame:
                stdout.write(frame["o"])
                stdout.flush()
            else:
                stderr.write(frame.get("e", ""))
                stderr.flush()
    except OSError:
        pass
    finally:
        reader.close()
        sock.close()
    raise DaemonUnavailable("the daemon closed the connection")
