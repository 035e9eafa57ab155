"""The lab machine service's wire format: one JSON object per line, one request per connection.

A request is `{"op": name, ...arguments}`; the answer is `{"ok": true, ...}` or
`{"ok": false, "error": sentence, "hint": next step}`. Pure code: no ROS, no sockets.
"""

from __future__ import annotations

import json
from typing import Any

__all__ = ["SOCKET_ENV", "decode", "encode", "failure"]

SOCKET_ENV = "COURSE_LAB_SOCKET"  # set by `make lab` for JupyterLab, its kernels and terminals
MAX_LINE = 1 << 20


def encode(message: dict[str, Any]) -> bytes:
    """Return one message as a JSON line."""
    return json.dumps(message, separators=(",", ":")).encode() + b"\n"


def decode(line: bytes) -> dict[str, Any]:
    """Return the message of one JSON line; raise ValueError on anything else."""
    message = json.loads(line.decode())
    if not isinstance(message, dict):
        raise ValueError("a message must be a JSON object")
    return message


def failure(error: str, hint: str = "") -> dict[str, Any]:
    """Return a failed answer."""
    return {"ok": False, "error": error, "hint": hint}
