"""A kernel's (or terminal's) door to its lab's machine service; None outside a lab."""

from __future__ import annotations

import os
import socket
from pathlib import Path
from typing import Any

from ..core.errors import CourseError
from .protocol import MAX_LINE, SOCKET_ENV, decode, encode

__all__ = ["MachineClient", "machine_client"]


class MachineClient:
    """Send requests to the machine service listening on one Unix socket."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def __repr__(self) -> str:
        return f"<MachineClient {self.path.name}>"

    def request(self, op: str, *, timeout: float = 60.0, **arguments: Any) -> dict[str, Any]:
        """Send one request and return the answer; raise CourseError when it failed."""
        try:
            with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as sock:
                sock.settimeout(timeout)
                sock.connect(str(self.path))
                sock.sendall(encode({"op": op, **arguments}))
                answer = sock.makefile("rb").readline(MAX_LINE)
        except OSError as exc:
            raise CourseError(
                f"The lab's machine service does not answer ({exc}).",
                hint="is `make lab` still running? Start it again, then re-run this cell.",
            ) from exc
        if not answer:
            raise CourseError(
                "The lab's machine service closed the connection without an answer.",
                hint="look at the terminal that runs `make lab`; then re-run this cell.",
            )
        message = decode(answer)
        if not message.get("ok"):
            raise CourseError(str(message.get("error")), hint=str(message.get("hint") or ""))
        return message


def machine_client(environ: dict[str, str] | None = None) -> MachineClient | None:
    """Return the client of this process's lab, or None outside a lab (or if it is gone)."""
    env = os.environ if environ is None else environ
    path = env.get(SOCKET_ENV, "")
    if not path or not Path(path).is_socket():
        return None
    return MachineClient(Path(path))
