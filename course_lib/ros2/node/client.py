"""The course's client node: its view of the graph (graph_client.py), its calls to nodes'
parameter services (param_calls.py) and the journal of the changes it asks for
(set_journal.py), behind the one object every door uses."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from typing import Any

from ..results import Descriptor, NodeInfo, NodeName, SetResult, TopicInfo
from ..values import ParamValue, journal_value
from .discovery import GraphView
from .graph_client import DISCOVERY_WAIT_S, YOUNG_CLIENT_S, GraphClient
from .param_calls import SERVICE_WAIT_S, ParamCalls, ServiceCallError
from .set_journal import SetJournal, Stored

__all__ = [
    "DISCOVERY_WAIT_S",
    "SERVICE_WAIT_S",
    "YOUNG_CLIENT_S",
    "RosClient",
    "ServiceCallError",
]


class RosClient:
    """Graph queries and parameter calls over one long-lived rclpy node (thread-safe)."""

    def __init__(
        self,
        node: Any,
        wait_future: Callable[[Any, float], Any],
        *,
        born: float | None = None,
    ) -> None:
        self.node = node
        self.calls = ParamCalls(node, wait_future)
        self.graph = GraphClient(
            node, answers=lambda name, timeout: self.answers(name, timeout=timeout), born=born
        )
        self.journal = SetJournal(node.context.get_domain_id())

    # -- the graph (GraphClient) ---------------------------------------------------------
    def settle(self, *, min_age_s: float = 0.0) -> None:
        """Wait until this client has discovered the whole graph (at once when it is warm)."""
        self.graph.settle(min_age_s=min_age_s)

    def wait_joined(self) -> None:
        """Wait (a warm client) until a node whose process is starting has been seen whole."""
        self.graph.wait_joined()

    def wait_all_seen(self, timeout: float) -> bool:
        """Wait until every participant of the domain on this host is seen; return whether."""
        return self.graph.wait_all_seen(timeout)

    def graph_view(self) -> GraphView:
        """Return the node and topic names seen, and what is known to be missing from them."""
        return self.graph.graph_view()

    @property
    def uses_sim_time(self) -> bool:
        """Return whether this client's node runs on simulation time (`--use-sim-time`)."""
        return self.graph.uses_sim_time

    def node_names(self, *, include_hidden: bool = False) -> list[NodeName]:
        """Return the nodes the graph shows (hidden ones only if asked), less ghosts."""
        return self.graph.node_names(include_hidden=include_hidden)

    def wait_for_node(
        self,
        full_name: str,
        *,
        include_hidden: bool,
        timeout: float,
        clock: Callable[[], float] = time.monotonic,
        sleep: Callable[[float], None] = time.sleep,
    ) -> bool:
        """Wait (bounded) until `full_name` is in the graph; return whether it is."""
        return self.graph.wait_for_node(
            full_name, include_hidden=include_hidden, timeout=timeout, clock=clock, sleep=sleep
        )

    def wait_for(
        self,
        found: Callable[[], bool],
        *,
        timeout: float,
        limit: float = math.inf,
        clock: Callable[[], float] = time.monotonic,
        sleep: Callable[[float], None] = time.sleep,
    ) -> bool:
        """Wait until `found()`, as `wait_for_node` waits for a node; `limit` caps the wait."""
        return self.graph.wait_for(found, timeout=timeout, limit=limit, clock=clock, sleep=sleep)

    def graph_complete(self) -> bool:
        """Return whether this client knows the whole domain."""
        return self.graph.graph_complete()

    def topics(self, *, include_hidden: bool = False) -> list[TopicInfo]:
        """Return the topics with their types, in the graph's order."""
        return self.graph.topics(include_hidden=include_hidden)

    def node_info(self, full_name: str, *, include_hidden: bool = False) -> NodeInfo:
        """Return the publishers, subscribers, services and actions of one node."""
        return self.graph.node_info(full_name, include_hidden=include_hidden)

    def age(self) -> float:
        """Return how long this client node has been discovering the graph, in seconds."""
        return self.graph.age()

    # -- parameter services (ParamCalls) and the journal (SetJournal) --------------------
    def services_ready(self, node_name: str, *, timeout: float = SERVICE_WAIT_S) -> bool:
        """Wait until the node's parameter services answer requests; False after `timeout`."""
        return self.calls.services_ready(node_name, timeout=timeout)

    def answers(self, node_name: str, *, timeout: float) -> bool:
        """Return whether the node answers a parameter request within `timeout`."""
        return self.calls.answers(node_name, timeout=timeout)

    def list_parameters(self, node_name: str, prefixes: Sequence[str] = ()) -> list[str]:
        """Return the names of the node's parameters (optionally under `prefixes`)."""
        return self.calls.list_parameters(node_name, prefixes)

    def describe_parameters(self, node_name: str, names: Sequence[str]) -> list[Descriptor]:
        """Return the descriptors of `names`."""
        return self.calls.describe_parameters(node_name, names)

    def get_parameters(self, node_name: str, names: Sequence[str]) -> list[ParamValue]:
        """Return the values of `names` (an unknown name yields no value or NOT_SET)."""
        values = self.calls.get_parameters(node_name, names)
        self.journal.learn(node_name, names, values, self.calls.reply_writers(node_name))
        return values

    def set_parameters(
        self, node_name: str, values: Sequence[tuple[str, ParamValue]]
    ) -> list[SetResult]:
        """Set each parameter on its own (not atomically); return one result per parameter.

        The request is written to the lab's parameter journal first, with the values it
        replaces, so that the node's /parameter_events can be traced to this door. Those
        values are known without a request (set_journal.py), but for a parameter this client
        has never read nor seen changed since the node started: that one is read first.
        """
        names = [name for name, _v in values]
        writers = self.calls.reply_writers(node_name)
        old = self.journal.old_values(node_name, names, writers)
        unknown = [name for name in names if name not in old]
        if unknown:
            old.update(self._read_old(node_name, unknown))
            writers = writers or self.calls.reply_writers(node_name)
        marks = self.journal.record_request(node_name, values, old, writers)
        try:
            results = self.calls.set_parameters(node_name, values, writers=writers or None)
        except ServiceCallError:
            self.journal.record_lost(node_name, names)
            raise
        self.journal.record_answer(node_name, values, marks, results)
        return results

    def _read_old(self, node_name: str, names: Sequence[str]) -> dict[str, Stored | None]:
        """Read values nothing else knows from the node (None: no answer, or no such name)."""
        try:
            read = self.get_parameters(node_name, names)
        except ServiceCallError:
            read = []
        if len(read) != len(names):  # a get answers nothing if one name is undeclared
            return dict.fromkeys(names)
        return {name: journal_value(value) for name, value in zip(names, read, strict=True)}

    def close(self) -> None:
        """Destroy the cached service clients."""
        self.calls.close()
