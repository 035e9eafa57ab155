"""The socket probes: a TCP port nothing on 127.0.0.1 holds right now, a Unix socket that
answers."""

from __future__ import annotations

import os
import socket

__all__ = ["free_port", "unix_socket_answers"]


def free_port(host: str = "127.0.0.1") -> int:
    """Return a TCP port free on `host` right now (another process may take it after)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind((host, 0))
        return int(probe.getsockname()[1])


def unix_socket_answers(path: str | os.PathLike[str]) -> bool:
    """Return whether a process listens on the Unix socket at `path` (a file that a killed
    server left refuses the connection)."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as probe:
        try:
            probe.connect(os.fspath(path))
        except OSError:
            return False
    return True
