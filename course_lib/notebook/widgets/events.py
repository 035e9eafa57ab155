"""/parameter_events as data (`ParameterChange`) and as a live table widget."""

from __future__ import annotations

import html
import threading
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = ["EventsTable", "ParameterChange", "changes_of", "subscribe_parameter_events"]


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


def subscribe_parameter_events(session: Any, callback: Callable[[Any], None]) -> Any:
    """Subscribe the session's node to /parameter_events; return the subscription."""
    from rcl_interfaces.msg import ParameterEvent
    from rclpy.qos import qos_profile_parameter_events

    return session.node.create_subscription(
        ParameterEvent, "/parameter_events", callback, qos_profile_parameter_events
    )


class EventsTable:
    """A live table of /parameter_events (newest first), for any node of the session's domain."""

    def __init__(self, session: Any, rows: int = 12) -> None:
        import ipywidgets as widgets

        self.session = session
        self.changes: deque[ParameterChange] = deque(maxlen=200)
        self.rows = rows
        self.widget = widgets.HTML(self._html())
        self._lock = threading.Lock()
        self._sub = subscribe_parameter_events(session, self._on_event)

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
        if not self.session.closed:
            self.session.node.destroy_subscription(self._sub)
