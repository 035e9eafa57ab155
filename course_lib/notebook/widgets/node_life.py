"""Whether a node a widget shows still runs, and how to start it again (issue 59).

One look-up of the session's graph every LOOK_S, in the session's executor, serves every node
followed in that session: no service call, no busy polling, and no timer at all while nothing
is followed. A node is known by its /parameter_events publishers' GIDs, so a node stopped and
started again between two look-ups is still seen to be another one.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ...core.errors import CourseError
from ...session.per_session import PerSession
from ..start_command import last_start_command

__all__ = [
    "LOOK_S",
    "GraphWatch",
    "Identity",
    "NodeNotRunningError",
    "Stopped",
    "graph_watch",
    "start_command",
    "stopped_now",
]

_log = logging.getLogger(__name__)

LOOK_S = 0.5  # two graph look-ups a second for all followed nodes (each well under 1 ms)
PARAMETER_EVENTS = "/parameter_events"

Identity = frozenset[bytes]  # empty while the node does not run


def _full_name(namespace: str, name: str) -> str:
    return namespace.rstrip("/") + "/" + name


class GraphWatch:
    """Look the followed nodes up in one session's graph, LOOK_S apart, and tell each follower
    what it found (its node's identity) on every look-up."""

    def __init__(self, session: Any) -> None:
        self.session = session
        self._followers: dict[int, tuple[str, Callable[[Identity], None]]] = {}
        self._lock = threading.Lock()
        self._timer: Any = None
        # nodes once seen with a /parameter_events publisher: for them the name alone never
        # says "running" (a stopped node's name can linger in the graph's node list: the ghost
        # of ros2/ros2#1413; ci saw a panel that never said its stopped node was gone)
        self._with_events: set[str] = set()

    def identity(self, node: str) -> Identity:
        """Return the GIDs of `node`'s /parameter_events publishers (a node made without one:
        its name while the graph lists it); empty if it does not run."""
        return self._identities({node})[node]

    def _identities(self, nodes: set[str]) -> dict[str, Identity]:
        graph = self.session.node
        gids: dict[str, set[bytes]] = {node: set() for node in nodes}
        for info in graph.get_publishers_info_by_topic(PARAMETER_EVENTS):
            full = _full_name(info.node_namespace, info.node_name)
            if full in gids:
                gids[full].add(bytes(info.endpoint_gid))
        with self._lock:
            self._with_events |= {node for node, found in gids.items() if found}
            by_name = {node for node, found in gids.items() if not found} - self._with_events
        if by_name:
            listed = {_full_name(ns, n) for n, ns in graph.get_node_names_and_namespaces()}
            for node, found in gids.items():
                if node in by_name and node in listed:
                    found.add(node.encode())
        return {node: frozenset(found) for node, found in gids.items()}

    def look(self) -> None:
        """Look every followed node up now and tell its followers (an error is logged: raised
        in the session's executor, it would end the session's ROS thread)."""
        with self._lock:
            followers = list(self._followers.values())
        if not followers or self.session.closed:
            return
        try:
            found = self._identities({node for node, _ in followers})
        except Exception:  # the session closing under the look-up
            _log.exception("a graph look-up failed")
            return
        for node, callback in followers:
            try:
                callback(found[node])
            except Exception:  # one widget's error never silences another
                _log.exception("a follower of %s failed", node)

    def follow(self, node: str, callback: Callable[[Identity], None]) -> Callable[[], None]:
        """Call `callback` with `node`'s identity on every look-up; return what stops it."""
        key = id(callback)
        with self._lock:
            self._followers[key] = (node, callback)
            if self._timer is None:
                self._timer = self.session.node.create_timer(LOOK_S, self.look)

        def stop() -> None:
            with self._lock:
                self._followers.pop(key, None)
                timer = self._timer if not self._followers else None
                if timer is not None:
                    self._timer = None
            if timer is not None and not self.session.closed:
                self.session.node.destroy_timer(timer)

        return stop


graph_watch = PerSession(GraphWatch)  # graph_watch(session): the session's one graph watch


@dataclass(frozen=True)
class Stopped:
    """A node that left the graph: when it was seen gone, and how to start it again."""

    node: str
    when: str  # "sim time 12.3 s", or the wall clock without a simulation
    command: str | None  # the `%ros2 run` line that starts it, if the course knows it

    @property
    def remedy(self) -> str:
        """Return what to do: the command, or the cell that starts the node."""
        if self.command:
            return f"start it again with `{self.command}`"
        return "run the cell that starts it"

    @property
    def line(self) -> str:
        """Return the one line a widget shows while the node is gone."""
        return f"{self.node} is not running (stopped at {self.when}): {self.remedy}"


class NodeNotRunningError(CourseError):
    """A widget was asked for the values of a node that has stopped."""

    def __init__(self, stopped: Stopped) -> None:
        super().__init__(
            f"{stopped.node} is not running (stopped at {stopped.when}): "
            "the panel cannot read its values",
            hint=f"{stopped.remedy}; the panel reads them again once it runs.",
        )
        self.stopped = stopped


def stopped_now(session: Any, node: str, command: str | None) -> Stopped:
    """Return a Stopped for `node`, seen gone now (simulated time if a world is shown)."""
    from .events import sim_now

    sim = sim_now(session)
    when = f"sim time {sim:.1f} s" if sim is not None else time.strftime("%H:%M:%S")
    return Stopped(node, when, command)


def start_command(session: Any, node: str) -> str | None:
    """Return the `%ros2 run` line that started `node` last in this session's lab, or None."""
    return last_start_command(node, session.domain_id, session.env)
