"""The command sockets that killed view servers leave are removed; nothing live is."""

from __future__ import annotations

import socket
import subprocess
from pathlib import Path

from course_lib.core.paths import runtime_dir
from course_lib.viz.command_sockets import command_socket_url, remove_dead_command_sockets


def _dead_pid() -> int:
    """Return the pid of a process that has ended (reaped)."""
    child = subprocess.Popen(["true"])
    child.wait()
    return child.pid


def _bound(path: Path, *, listening: bool) -> socket.socket:
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    sock.bind(str(path))
    if listening:
        sock.listen()
    return sock


def test_only_the_sockets_of_gone_servers_are_removed() -> None:
    folder = runtime_dir()
    mine = Path(command_socket_url().removeprefix("ipc://"))  # this process's, to be bound
    own = _bound(mine, listening=False)  # bound, not listening yet: its pid runs
    killed = folder / f"meshcat-{_dead_pid()}.sock"  # its server was killed: the file stays
    _bound(killed, listening=False).close()
    # a server of another PID namespace (its pid means nothing here) still answers
    elsewhere = folder / f"meshcat-{_dead_pid()}.sock"
    listener = _bound(elsewhere, listening=True)
    try:
        assert killed.exists()
        removed = remove_dead_command_sockets()
        assert killed in removed and not killed.exists()
        assert elsewhere.exists() and mine.exists()
        assert elsewhere not in removed and mine not in removed
    finally:
        listener.close()
        own.close()
        for path in (killed, elsewhere, mine):
            path.unlink(missing_ok=True)


def test_a_new_server_removes_what_killed_ones_left() -> None:
    killed = runtime_dir() / f"meshcat-{_dead_pid()}.sock"
    _bound(killed, listening=False).close()
    url = command_socket_url()
    try:
        assert not killed.exists()
    finally:
        Path(url.removeprefix("ipc://")).unlink(missing_ok=True)
        killed.unlink(missing_ok=True)
