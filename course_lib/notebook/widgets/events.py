"""/parameter_events as data (`ParameterChange`) and as a live table widget."""

from __future__ import annotations

import contextlib
import html
import logging
import threading
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ...session.per_session import PerSession

__all__ = [
    "EventsTable",
    "ParameterChange",
    "ParameterEventsFeed",
    "changes_of",
    "parameter_events",
    "sim_now",
    "subscribe_parameter_events",
]

_log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ParameterChange:
    """One parameter of one /parameter_events message."""

    node: str
    kind: str  # new, changed, deleted
    name: str
    value: Any


def changes_of(msg: Any) -> list[ParameterChange]:
    """Return the changes one ParameterEvent message carries."""
    from rclpy.parameter import parameter_value_to_python

    out = []
    for kind, params in (
        ("new", msg.new_parameters),
        ("changed", msg.changed_parameters),
        ("deleted", msg.deleted_parameters),
    ):
        for p in params:
            value = None if kind == "deleted" else parameter_value_to_python(p.value)
            out.append(ParameterChange(msg.node, kind, p.name, value))
    return out


class ParameterEventsFeed:
    """One /parameter_events subscription per session, shared by every widget that listens.

    A lesson makes it when it starts, long before it changes a parameter: a subscription made
    the moment before a change may not be matched yet by the node's publisher (parameter
    events are volatile), and that change would never arrive.
    """

    def __init__(self, session: Any) -> None:
        from rcl_interfaces.msg import ParameterEvent
        from rclpy.qos import qos_profile_parameter_events

        from ...session.quiet_events import quiet_subscription

        self._listeners: list[Callable[[Any], None]] = [self._journal]
        self._lock = threading.Lock()
        self._session = session
        self._sub = session.node.create_subscription(
            ParameterEvent,
            "/parameter_events",
            self._on_event,
            qos_profile_parameter_events,
            event_callbacks=quiet_subscription(),
        )

    def _on_event(self, msg: Any) -> None:
        with self._lock:
            listeners = list(self._listeners)
        for listener in listeners:
            try:
                listener(msg)
            except Exception:  # one widget's error never silences another: logged, not raised
                _log.exception("a /parameter_events listener failed")

    def _journal(self, msg: Any) -> None:
        """Write the event to the lab's parameter journal (lesson.history reads it)."""
        from ...core import param_journal
        from ...ros2.values import event_record

        record = event_record(msg, sim_now(self._session))
        if record is not None:
            param_journal.append(self._session.domain_id, record)

    def listen(self, callback: Callable[[Any], None]) -> Callable[[], None]:
        """Call `callback` with every ParameterEvent from now on; return what stops it."""
        with self._lock:
            self._listeners.append(callback)

        def stop() -> None:
            with self._lock, contextlib.suppress(ValueError):
                self._listeners.remove(callback)

        return stop


def sim_now(session: Any) -> float | None:
    """Return the simulated time of the world this kernel shows, if any (from /odom)."""
    from ..world import _worlds

    world = _worlds.get(id(session))
    latest = getattr(world, "_latest", None)
    return None if latest is None else round(latest.time_s, 3)


# parameter_events(session): the session's /parameter_events feed, subscribing the first time
parameter_events = PerSession(ParameterEventsFeed)


def subscribe_parameter_events(
    session: Any, callback: Callable[[Any], None]
) -> Callable[[], None]:
    """Call `callback` with each /parameter_events message of `session`'s domain; return
    what stops it."""
    return parameter_events(session).listen(callback)


class EventsTable:
    """A live table of /parameter_events (newest first), for any node of the session's domain."""

    def __init__(self, session: Any, rows: int = 12) -> None:
        import ipywidgets as widgets

        self.session = session
        self.changes: deque[ParameterChange] = deque(maxlen=200)
        self.rows = rows
        self.widget = widgets.HTML(self._html())
        self._lock = threading.Lock()
        self._stop_listening = subscribe_parameter_events(session, self._on_event)

    def _on_event(self, msg: Any) -> None:
        with self._lock:
            self.changes.extend(c for c in changes_of(msg) if not c.node.startswith("/_"))
            self.widget.value = self._html()

    def _html(self) -> str:
        head = "".join(f"<th>{h}</th>" for h in ("node", "event", "parameter", "value"))
        body = "".join(
            f"<tr><td>{html.escape(c.node)}</td><td>{c.kind}</td><td>{html.escape(c.name)}</td>"
            f"<td>{html.escape(repr(c.value))}</td></tr>"
            for c in list(self.changes)[::-1][: self.rows]
        )
        return f"<b>/parameter_events</b><table><tr>{head}</tr>{body}</table>"

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)

    def close(self) -> None:
        """Stop listening."""
        self._stop_listening()
