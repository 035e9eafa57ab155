"""The session's one RosClient: made on first use, made again after a new session."""

from __future__ import annotations

import threading
from typing import Any

__all__ = ["client"]

_lock = threading.Lock()
_cached: tuple[Any, Any] | None = None  # (session, RosClient)


def client() -> Any:
    """Return the RosClient over the current session's node (re-made after a new session)."""
    global _cached
    from ...session.session import get_session
    from .client import RosClient

    session = get_session()
    with _lock:
        if _cached is None or _cached[0] is not session:
            _cached = (session, RosClient(session.node, session.wait_future))
        return _cached[1]
