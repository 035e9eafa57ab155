"""The one way to wait on a condition that has no event: poll it until true or a timeout."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TypeVar

__all__ = ["POLL_S", "wait_until"]

POLL_S = 0.02
T = TypeVar("T")


def wait_until(
    predicate: Callable[[], T],
    timeout: float,
    *,
    interval: float = POLL_S,
    message: str | None = None,
) -> T:
    """Poll `predicate` until it returns a true value or `timeout` seconds passed.

    Returns its last value (asked once more at the timeout), so `assert wait_until(...)`
    reads as the condition and a found value can be used at once.

    Raises:
        TimeoutError: with `message`, when one is given and the condition never held.
    """
    deadline = time.monotonic() + timeout
    while not (value := predicate()):
        if time.monotonic() >= deadline:
            value = predicate()
            if not value and message is not None:
                raise TimeoutError(message)
            return value
        time.sleep(interval)
    return value
