"""One object per course session, made the first time a session asks for it.

The kernel's shared readers (the samples feed, the parameter-events feed, the graph watch,
the run log) each exist once per session; this keeps them, and lets them go with it.
"""

from __future__ import annotations

import threading
import weakref
from collections.abc import Callable
from typing import Any, Generic, TypeVar

__all__ = ["PerSession"]

T = TypeVar("T")


class PerSession(Generic[T]):
    """Call it with a session: the session's one `make(session)`, made on the first call."""

    def __init__(self, make: Callable[[Any], T]) -> None:
        self._make = make
        self._made: weakref.WeakKeyDictionary[Any, T] = weakref.WeakKeyDictionary()
        self._lock = threading.Lock()

    def __call__(self, session: Any) -> T:
        with self._lock:
            made = self._made.get(session)
            if made is None:
                made = self._made[session] = self._make(session)
            return made
