"""The graph half of the course's client node: waiting for nodes, the settled-graph rule, node
and topic lists (RosClient composes it with the parameter calls and the journal)."""

from __future__ import annotations

import math
import os
import time
from collections import Counter
from collections.abc import Callable, Sequence
from typing import Any

from rclpy.node import NodeNameNonExistentError
from rclpy.topic_or_service_is_hidden import topic_or_service_is_hidden

from ...core.waiting import wait_until
from ..results import NodeInfo, NodeName, TopicInfo
from .discovery import (
    GHOST_GRACE_S,
    UNKNOWN_NODE,
    GraphView,
    profile_timing,
    wait_joined,
    wait_settled,
    without_ghosts,
)
from .participants import (
    domain_newcomers,
    endpoint_holders,
    participant_prefix,
    prefix_pid,
    read_bound_participants,
    unseen_participants,
)

__all__ = [
    "DISCOVERY_WAIT_S",
    "INCOMPLETE_WAIT_S",
    "SERVICES_GRACE_S",
    "SETTLED_QUIET_S",
    "YOUNG_CLIENT_S",
    "GraphClient",
]

# How long a node-targeted command looks for a node the graph does not show yet. The real
# tools wait 1 s (`--timeout`) and so miss freshly started nodes; the course waits longer.
DISCOVERY_WAIT_S = 2.5
# Until this age, a node may still be unknown to a fresh client (Fast DDS re-announces every
# 3 s by default), so node lookups wait at least until the client is this old.
YOUNG_CLIENT_S = 4.0
# A node missing from a graph known whole for this long is not there: "Node not found" at
# once, not after DISCOVERY_WAIT_S (a just-started node is waited for: graph_complete).
SETTLED_QUIET_S = 0.15
# While participants bound on this host are still unseen (a fresh client, or a starved process
# on a busy host: seen taking over 4 s), a node lookup waits up to this long before "not found".
INCOMPLETE_WAIT_S = 12.0
# A joining node's parameter services follow its name within this long, or it has none
# (`start_parameter_services=False`: it never answers, so nothing waits for its answer).
SERVICES_GRACE_S = 1.0
_POLL_S = 0.02


def _is_hidden_name(name: str) -> bool:
    return any(part.startswith("_") for part in name.split("/"))


def _topics(
    pairs: Sequence[tuple[str, Sequence[str]]], include_hidden: bool
) -> tuple[TopicInfo, ...]:
    return tuple(
        TopicInfo(n, tuple(t)) for n, t in pairs if include_hidden or not _is_hidden_name(n)
    )


class GraphClient:
    """What one long-lived rclpy node sees of the graph, and when it has seen all of it."""

    def __init__(
        self,
        node: Any,
        *,
        answers: Callable[[str, float], bool],
        born: float | None = None,
    ) -> None:
        """`answers(node_name, timeout)`: whether a node answers a parameter request."""
        self.node = node
        self._answers = answers
        self._born = time.monotonic() if born is None else born
        # This process's participant reads the course's Fast DDS profile from its environment.
        self._timing = profile_timing(os.environ.get("FASTRTPS_DEFAULT_PROFILES_FILE"))
        self._domain_id: int = node.context.get_domain_id()
        # When this client first listed each node name it lists now (see node_names).
        self._first_listed: dict[str, float] = {}

    def settle(self, *, min_age_s: float = 0.0) -> None:
        """Wait until this client has discovered the whole graph (at once when it is warm).

        `min_age_s` is `--spin-time`: a client younger than that waits until it is that old.
        """
        wait_settled(
            self.graph_view,
            born=self._born,
            timing=self._timing,
            min_age_s=min_age_s,
            starting=self._starting,
            spinning=self._spinning,
        )

    def _starting(self) -> frozenset[int]:
        return frozenset(domain_newcomers(self._domain_id, joined=True))

    def _spinning(self, pids: frozenset[int], timeout: float) -> bool:
        """Wait (at most `timeout` s) until every named node of these processes (the low 16
        bits of their pids, as participants carry them) answers a parameter request; return
        whether all did. Hidden nodes (the course's own clients) and nodes made without
        parameter services never answer: the graph's quiet tells when those are whole."""
        deadline = time.monotonic() + timeout
        holders, _settled = self._holders()
        named = [
            name
            for name, prefixes in holders.items()
            if not _is_hidden_name(name) and any(prefix_pid(p) in pids for p in prefixes)
        ]
        # a node's name can come before its services: they have a moment to show (each node
        # is looked up until they do, not again)
        offering: set[str] = set()

        def all_offer() -> bool:
            offering.update(n for n in named if n not in offering and self._offers_parameters(n))
            return len(offering) == len(named)

        wait_until(all_offer, min(SERVICES_GRACE_S, timeout))
        return all(
            self._answers(name, max(0.0, deadline - time.monotonic()))
            for name in named
            if name in offering
        )

    def _offers_parameters(self, full_name: str) -> bool:
        """Return whether the graph shows the node's `list_parameters` service (rclpy makes
        it in the node's constructor, unless `start_parameter_services=False`)."""
        namespace, _, name = full_name.rpartition("/")
        try:
            services = self.node.get_service_names_and_types_by_node(name, namespace or "/")
        except NodeNameNonExistentError:
            return False
        return any(service == f"{full_name}/list_parameters" for service, _types in services)

    def wait_joined(self) -> None:
        """Wait (a warm client) until a node whose process is starting has been seen whole:
        what a lookup counts (publishers, services) is then all of it, every time."""
        if self.age() >= self._timing.warm_s:
            wait_joined(
                self.graph_view,
                self._timing,
                self._starting,
                time.monotonic,
                time.sleep,
                self._spinning,
            )

    def wait_all_seen(self, timeout: float) -> bool:
        """Wait (at most `timeout` s) until this client has discovered every participant its
        domain has on this host, e.g. a node just started; return whether it has."""
        deadline = time.monotonic() + timeout
        while True:
            view = self.graph_view()
            if not view.missing_participants and not view.unknown_endpoints:
                return True
            if time.monotonic() >= deadline:
                return False
            time.sleep(_POLL_S)

    def graph_view(self) -> GraphView:
        """Return the node and topic names seen, and what is known to be missing from them."""
        node = self.node
        topics = [name for name, _types in node.get_topic_names_and_types()]
        endpoints = [
            info
            for name in topics
            for infos in (
                node.get_publishers_info_by_topic(name),
                node.get_subscriptions_info_by_topic(name),
            )
            for info in infos
        ]
        unknown = sum(info.node_name == UNKNOWN_NODE for info in endpoints)
        bound = read_bound_participants(self._domain_id)
        seen = {participant_prefix(info.endpoint_gid) for info in endpoints}
        missing = None if bound is None else unseen_participants(bound, seen)
        nodes = frozenset(n.full_name for n in self.node_names(include_hidden=True))
        pids = frozenset(prefix_pid(prefix) for prefix in seen)
        return GraphView(nodes, frozenset(topics), unknown, missing, len(endpoints), pids)

    @property
    def uses_sim_time(self) -> bool:
        """Return whether this client's node runs on simulation time (`--use-sim-time`)."""
        return bool(self.node.get_parameter("use_sim_time").value)

    def node_names(self, *, include_hidden: bool = False) -> list[NodeName]:
        """Return the nodes the graph shows (hidden ones only if asked), less the ghosts of
        nodes that have left (`discovery.without_ghosts`). A name just listed without an
        endpoint is waited for (at most GHOST_GRACE_S): a new node's endpoints follow its name,
        a ghost's never do."""
        deadline = time.monotonic() + GHOST_GRACE_S + 0.5
        while True:
            listed = [
                NodeName(name, ns, ns + ("" if ns.endswith("/") else "/") + name)
                for name, ns in self.node.get_node_names_and_namespaces()
            ]
            full = [n.full_name for n in listed]
            now = time.monotonic()
            first = self._first_listed
            self._first_listed = first = {name: first.get(name, now) for name in full}
            if not self._may_list_ghosts(listed):
                break
            holders, settled = self._holders()
            ages = {name: now - since for name, since in first.items()}
            young = [n for n in full if not holders.get(n) and ages[n] < GHOST_GRACE_S]
            if settled and young and now < deadline:
                time.sleep(_POLL_S)
                continue
            kept = Counter(without_ghosts(full, holders, settled, listed_for=ages))
            unique = []
            for name in listed:
                if kept[name.full_name] > 0:
                    kept[name.full_name] -= 1
                    unique.append(name)
            listed = unique
            break
        return [n for n in listed if include_hidden or (n.name and not n.name.startswith("_"))]

    def _may_list_ghosts(self, listed: Sequence[NodeName]) -> bool:
        """Return whether a name is listed twice, or without an endpoint of its own (a ghost
        has none); the full search of the graph (`_holders`) runs only then."""
        if len({n.full_name for n in listed}) < len(listed):
            return True
        node = self.node
        queries = (
            node.get_publisher_names_and_types_by_node,
            node.get_service_names_and_types_by_node,
            node.get_subscriber_names_and_types_by_node,
            node.get_client_names_and_types_by_node,
        )
        for name in listed:
            try:
                if not any(query(name.name, name.namespace) for query in queries):
                    return True
            except NodeNameNonExistentError:
                return True  # it left while we looked: the graph is changing
        return False

    def _holders(self) -> tuple[dict[str, set[tuple[int, ...]]], bool]:
        """Return the participants holding endpoints of each node name, and whether every
        participant bound on this host has been seen (the graph is settled)."""
        node = self.node
        holders = endpoint_holders(
            info
            for topic, _types in node.get_topic_names_and_types(no_demangle=True)
            for query in (node.get_publishers_info_by_topic, node.get_subscriptions_info_by_topic)
            for info in query(topic, no_mangle=True)
        )
        bound = read_bound_participants(self._domain_id)
        seen = set().union(*holders.values()) if holders else set()
        return holders, bound is not None and unseen_participants(bound, seen) == 0

    def wait_for_node(
        self,
        full_name: str,
        *,
        include_hidden: bool,
        timeout: float,
        clock: Callable[[], float] = time.monotonic,
        sleep: Callable[[float], None] = time.sleep,
    ) -> bool:
        """Wait (bounded, at least DISCOVERY_WAIT_S) until `full_name` is in the graph; while
        this host has participants of the domain the client has not seen, or has seen without
        their node names yet, up to INCOMPLETE_WAIT_S. (`clock` and `sleep`: as in
        `wait_settled`.)"""

        hidden = _is_hidden_name(full_name.rsplit("/", 1)[-1])
        quick = getattr(self.node, "listed_and_running", None)  # a LiveGraphNode's

        def found() -> bool:
            if quick is not None and (include_hidden or not hidden) and quick(full_name):
                return True  # listed, and its process runs: no search of the whole graph
            names = self.node_names(include_hidden=include_hidden)
            return full_name in {n.full_name for n in names}

        return self.wait_for(found, timeout=timeout, clock=clock, sleep=sleep)

    def wait_for(
        self,
        found: Callable[[], bool],
        *,
        timeout: float,
        limit: float = math.inf,
        clock: Callable[[], float] = time.monotonic,
        sleep: Callable[[float], None] = time.sleep,
    ) -> bool:
        """Wait until `found()` (a node, a topic) as `wait_for_node` does: a graph known whole
        for SETTLED_QUIET_S that still lacks it is an answer ("not there") at once. `limit`
        caps the whole wait."""
        start = clock()
        deadline = start + max(float(timeout), DISCOVERY_WAIT_S, YOUNG_CLIENT_S - self.age())
        complete_since: float | None = None
        while not found():
            now = clock()
            if now - start >= limit:
                return found()
            if now >= deadline:
                view = self.graph_view()  # a participant unseen, or seen with nameless endpoints
                partial = bool(view.missing_participants) or bool(view.unknown_endpoints)
                if not partial or now - start >= INCOMPLETE_WAIT_S:
                    return found()  # a last look: it may have come with that view
            if self.graph_complete():
                complete_since = now if complete_since is None else complete_since
                if now - complete_since >= SETTLED_QUIET_S:
                    return found()  # the whole domain is known: it is in it or not
            else:
                complete_since = None
            sleep(_POLL_S)
        return True

    def graph_complete(self) -> bool:
        """Return whether this client knows the whole domain: it is warm, has seen every
        participant bound on this host with every endpoint's node named, and no process of
        the domain is young enough to be starting a node that has not joined DDS yet."""
        if self.age() < self._timing.warm_s:
            return False
        view = self.graph_view()
        if view.missing_participants != 0 or view.unknown_endpoints:
            return False  # None: /proc cannot count participants here
        if domain_newcomers(self._domain_id):
            return False  # a process of the domain is starting: its node may follow
        # a young process that joined: seen by its pid (a count is fooled by the lingering
        # participant of a node just stopped)
        young = domain_newcomers(self._domain_id, joined=True)
        return all(pid & 0xFFFF in view.participant_pids for pid in young)

    def topics(self, *, include_hidden: bool = False) -> list[TopicInfo]:
        """Return the topics with their types, in the graph's order."""
        return [
            TopicInfo(name, tuple(types))
            for name, types in self.node.get_topic_names_and_types()
            if include_hidden or not topic_or_service_is_hidden(name)
        ]

    def node_info(self, full_name: str, *, include_hidden: bool = False) -> NodeInfo:
        """Return the publishers, subscribers, services and actions of one node."""
        name = full_name.rsplit("/", 1)[-1]
        namespace = full_name.rsplit("/", 1)[0] or "/"
        # rclpy.action imports its messages, and with them numpy (9 MiB): only when asked
        from rclpy.action.graph import (
            get_action_client_names_and_types_by_node,
            get_action_server_names_and_types_by_node,
        )

        node = self.node
        by_node = (name, namespace)
        return NodeInfo(
            name=full_name,
            subscribers=_topics(
                node.get_subscriber_names_and_types_by_node(*by_node), include_hidden
            ),
            publishers=_topics(
                node.get_publisher_names_and_types_by_node(*by_node), include_hidden
            ),
            service_servers=_topics(
                node.get_service_names_and_types_by_node(*by_node), include_hidden
            ),
            service_clients=_topics(
                node.get_client_names_and_types_by_node(*by_node), include_hidden
            ),
            action_servers=_topics(
                get_action_server_names_and_types_by_node(node, *by_node), include_hidden
            ),
            action_clients=_topics(
                get_action_client_names_and_types_by_node(node, *by_node), include_hidden
            ),
        )

    def age(self) -> float:
        """Return how long this client node has been discovering the graph, in seconds."""
        return time.monotonic() - self._born
