"""Keep a one-shot publisher alive until what it published has been delivered.

The course publishes from its one long-lived client node (never a new node per command, as
ros2cli does). Such a publisher matches a subscription the node already knows at once, before
the subscriber's process has discovered the publisher in turn; whatever it publishes before
then reaches the subscription only if the publisher still exists when that process catches up.
On a busy machine that takes longer than ros2topic's keep-alive of 0.1 s (in a suite run the
docs' one Twist never reached turtlesim; a subscriber stopped for 1 s missed 4 messages of 5),
so a publisher lives on until every matched reliable subscription has acknowledged.
"""

from __future__ import annotations

import time
from typing import Any

__all__ = ["ACK_POLL_S", "UNACKNOWLEDGED_LIMIT_S", "keep_until_acknowledged"]

ACK_POLL_S = 0.02
# How long a subscriber's process may lag (or a vanished one be waited for) at most. At 2 s,
# a subscriber stopped for 1 s on 2 busy cores had not caught up when the publisher went
# (ci93: the lessons' topic_publish lost 1 message of 3); a caught-up one acknowledges in ms.
UNACKNOWLEDGED_LIMIT_S = 5.0


def keep_until_acknowledged(
    publisher: Any, *, keep_alive: float = 0.0, limit: float = UNACKNOWLEDGED_LIMIT_S
) -> bool:
    """Wait `keep_alive` s, then until every matched reliable subscription has acknowledged
    what `publisher` published (at most `limit` s more); return whether they all have.

    Each check returns at once: a blocking `wait_for_all_acked` holds back the resend that a
    late subscription asks for, so it would wait its whole timeout and deliver nothing.
    """
    from rclpy.duration import Duration

    time.sleep(keep_alive)
    at_once = Duration(nanoseconds=1)  # 0 would mean "no timeout" to some middlewares
    deadline = time.monotonic() + limit
    while not publisher.wait_for_all_acked(at_once):
        if time.monotonic() >= deadline:
            return False
        time.sleep(ACK_POLL_S)
    return True
