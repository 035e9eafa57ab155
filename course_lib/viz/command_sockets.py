"""The meshcat servers' command sockets: Unix sockets in the user's private runtime folder.

One per server process, named after its pid (`meshcat-<pid>.sock`); never a TCP port, so no
other account on the host can send the scene a command.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..core.host import procfs
from ..core.host.ports import unix_socket_answers
from ..core.paths import runtime_dir

__all__ = ["command_socket_url", "remove_dead_command_sockets"]


def command_socket_url(pid: int | None = None) -> str:
    """Return the ZMQ address of this process's command socket: private to this user.

    Sockets that killed servers left are removed first (else each killed world would leave
    its file in the runtime folder for ever).
    """
    remove_dead_command_sockets()
    path = runtime_dir() / f"meshcat-{pid or os.getpid()}.sock"
    path.unlink(missing_ok=True)  # a socket left by a killed server of a reused pid
    return f"ipc://{path}"


def remove_dead_command_sockets() -> list[Path]:
    """Remove the command sockets of servers that are gone; return them.

    Gone: no process has the pid in the file's name, and nothing answers on the socket (a
    server of another PID namespace sharing this folder still answers, and is kept).
    """
    removed = []
    for path in runtime_dir().glob("meshcat-*.sock"):
        pid = path.name.removeprefix("meshcat-").removesuffix(".sock")
        if not pid.isdigit() or procfs.pid_alive(int(pid)) or unix_socket_answers(path):
            continue
        path.unlink(missing_ok=True)
        removed.append(path)
    return removed
