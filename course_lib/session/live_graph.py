"""An rclpy node whose view of the graph leaves out what ended processes left behind.

A process killed (SIGKILL, the out-of-memory killer) sends DDS no goodbye: every other
participant keeps its node names, topics, endpoints and services until its lease ends. The
course's participants keep Fast DDS's default lease (20 s): a shorter one made a process
stopped for longer than the lease (SIGSTOP, a starved host) leave the graph for good, since
Fast DDS does not send its endpoints again to those that dropped it. So the course's client
nodes ask /proc instead: a participant whose process has ended is gone at once from what
they list and count (see `dds_participants.dead_participants`).
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Collection, Sequence
from typing import Any, TypeVar

from rclpy.expand_topic_name import expand_topic_name
from rclpy.node import Node, NodeNameNonExistentError
from rclpy.topic_endpoint_info import TopicEndpointInfo

from ..core.host import procfs
from .dds_participants import (
    dead_participants,
    endpoint_holders,
    participant_prefix,
    prefix_runs,
    read_bound_participants,
)

__all__ = ["LIVENESS_TTL_S", "TOOL_NODES", "LiveGraphNode"]

# How long one look at /proc and the graph answers for (a killed process is left out this
# long after its end at most; the graph queries of one command share one look).
LIVENESS_TTL_S = 0.05

# The course's own tool nodes: the kernels' clients (`_course_client_<pid>`) and the `ros2`
# commands' and daemons' (`_ros2cli_...`, named as ros2cli names its own).
TOOL_NODES = ("/_course_client_", "/_ros2cli_")

Prefix = tuple[int, ...]
Listed = TypeVar("Listed", bound=tuple[Any, ...])


def _full_name(name: str, namespace: str) -> str:
    return namespace.rstrip("/") + "/" + name


class LiveGraphNode(Node):
    """A `rclpy.node.Node` whose graph queries leave out ended processes' participants."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._domain_id: int = self.context.get_domain_id()
        self._look: tuple[float, dict[str, set[Prefix]], frozenset[Prefix]] | None = None

    def _liveness(self) -> tuple[dict[str, set[Prefix]], frozenset[Prefix]]:
        """Return the participants holding each node name's endpoints, and the dead ones."""
        now = time.monotonic()
        if self._look is not None and now - self._look[0] < LIVENESS_TTL_S:
            return self._look[1], self._look[2]
        holders = endpoint_holders(
            info
            for topic, _types in super().get_topic_names_and_types(no_demangle=True)
            if topic.startswith("rt/")
            for info in self._endpoints(topic, mangled=True)
        )
        seen = set().union(*holders.values()) if holders else set()
        bound = read_bound_participants(self._domain_id)
        dead = dead_participants(seen, bound, procfs.pids()) if seen else frozenset()
        self._look = (now, holders, dead)
        return holders, dead

    def _endpoints(self, topic: str, *, mangled: bool) -> list[TopicEndpointInfo]:
        return [
            *super().get_publishers_info_by_topic(topic, mangled),
            *super().get_subscriptions_info_by_topic(topic, mangled),
        ]

    def _runs(self, prefix: Prefix) -> bool:
        """Return whether the participant's process may run (False: it may have ended)."""
        return prefix_runs(prefix, procfs.pid_max())

    def _alive(self, infos: list[TopicEndpointInfo]) -> list[TopicEndpointInfo]:
        prefixes = {participant_prefix(info.endpoint_gid) for info in infos}
        if all(self._runs(prefix) for prefix in prefixes):
            return infos  # a participant whose process runs is never a dead one
        _holders, dead = self._liveness()
        if not dead:
            return infos
        return [info for info in infos if participant_prefix(info.endpoint_gid) not in dead]

    def _only_dead(self, topic: str, *, mangled: bool) -> bool:
        """Return whether every endpoint of `topic` (there is one at least) is a dead one's."""
        infos = self._endpoints(topic, mangled=mangled)
        return bool(infos) and not self._alive(infos)

    # endpoints and their counts

    def get_publishers_info_by_topic(
        self, topic_name: str, no_mangle: bool = False
    ) -> list[TopicEndpointInfo]:
        return self._alive(super().get_publishers_info_by_topic(topic_name, no_mangle))

    def get_subscriptions_info_by_topic(
        self, topic_name: str, no_mangle: bool = False
    ) -> list[TopicEndpointInfo]:
        return self._alive(super().get_subscriptions_info_by_topic(topic_name, no_mangle))

    def count_publishers(self, topic_name: str) -> int:
        if not self._liveness()[1]:
            return super().count_publishers(topic_name)
        return len(self.get_publishers_info_by_topic(topic_name))

    def count_subscribers(self, topic_name: str) -> int:
        if not self._liveness()[1]:
            return super().count_subscribers(topic_name)
        return len(self.get_subscriptions_info_by_topic(topic_name))

    # topics and services

    def get_topic_names_and_types(self, no_demangle: bool = False) -> list[tuple[str, list[str]]]:
        pairs = super().get_topic_names_and_types(no_demangle)
        if not self._liveness()[1]:
            return pairs
        return [
            (name, types)
            for name, types in pairs
            if not self._only_dead(name, mangled=no_demangle)
        ]

    def _service_topic(self, service: str, *, request: bool) -> str:
        full = expand_topic_name(service, self.get_name(), self.get_namespace())
        return f"rq{full}Request" if request else f"rr{full}Reply"

    def get_service_names_and_types(self) -> list[tuple[str, list[str]]]:
        """The services the graph shows, less those of ended processes only and those that
        only the course's own tool nodes' cached clients still name: a node stopped cleanly
        left its parameter services listed, as clients of the kernels' and daemons' nodes
        (ros2cli's daemon, whose lists the learner compares with, makes no clients)."""
        pairs = super().get_service_names_and_types()
        holders, dead = self._liveness()
        tools = {name: held for name, held in holders.items() if name.startswith(TOOL_NODES)}
        used: set[str] = set()
        for full in tools:
            namespace, _, name = full.rpartition("/")
            try:
                clients = super().get_client_names_and_types_by_node(name, namespace or "/")
            except NodeNameNonExistentError:
                continue  # it left while we looked
            used.update(service for service, _types in clients)
        if not dead and not used:
            return pairs
        tool_participants: set[Prefix] = set().union(*tools.values()) if tools else set()
        return [
            (name, types)
            for name, types in pairs
            if not ((dead or name in used) and self._service_gone(name, dead, tool_participants))
        ]

    def _service_gone(
        self, service: str, dead: Collection[Prefix], tools: Collection[Prefix]
    ) -> bool:
        """Return whether `service` has endpoints, none a live server's and none a live
        client's other than the tool nodes' (`tools`: their participants)."""
        request = self._service_topic(service, request=True)
        reply = self._service_topic(service, request=False)
        servers = [
            *super().get_subscriptions_info_by_topic(request, True),
            *super().get_publishers_info_by_topic(reply, True),
        ]
        clients = [
            *super().get_publishers_info_by_topic(request, True),
            *super().get_subscriptions_info_by_topic(reply, True),
        ]
        if not servers and not clients:
            return False  # named some other way: nothing known of it

        def live(info: TopicEndpointInfo, *, tool_ok: bool = True) -> bool:
            prefix = participant_prefix(info.endpoint_gid)
            return prefix not in dead and (tool_ok or prefix not in tools)

        return not any(live(i) for i in servers) and not any(
            live(i, tool_ok=False) for i in clients
        )

    def count_services(self, service_name: str) -> int:
        if not self._liveness()[1]:
            return super().count_services(service_name)
        request = self._service_topic(service_name, request=True)
        return len(self.get_subscriptions_info_by_topic(request, no_mangle=True))

    def count_clients(self, service_name: str) -> int:
        if not self._liveness()[1]:
            return super().count_clients(service_name)
        request = self._service_topic(service_name, request=True)
        return len(self.get_publishers_info_by_topic(request, no_mangle=True))

    # node names

    def _live_names(self, listed: Sequence[Listed]) -> list[Listed]:
        """Return `listed` ((name, namespace, ...) tuples) less the names of ended processes:
        a name held by a dead participant is listed once per live participant holding it."""
        holders, dead = self._liveness()
        if not dead:
            return list(listed)
        allowed = {name: len(held - dead) for name, held in holders.items() if held & dead}
        used: Counter[str] = Counter()
        kept = []
        for entry in listed:
            full = _full_name(entry[0], entry[1])
            if full in allowed:
                if used[full] >= allowed[full]:
                    continue
                used[full] += 1
            kept.append(entry)
        return kept

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        return self._live_names(super().get_node_names_and_namespaces())

    def get_node_names_and_namespaces_with_enclaves(self) -> list[tuple[str, str, str]]:
        return self._live_names(super().get_node_names_and_namespaces_with_enclaves())

    def listed_and_running(self, full_name: str) -> bool:
        """Return True if the graph lists `full_name` and a process holding its parameter
        service runs: the whole look (`get_node_names_and_namespaces`) would keep the name
        then, and this costs one endpoint query. False says nothing: a node without
        parameter services, or held by processes that have all ended."""
        listed = super().get_node_names_and_namespaces()
        if not any(_full_name(name, ns) == full_name for name, ns in listed):
            return False
        topic = f"rq{full_name}/get_parametersRequest"
        holders = {
            participant_prefix(info.endpoint_gid)
            for info in super().get_subscriptions_info_by_topic(topic, True)
            if _full_name(info.node_name, info.node_namespace) == full_name
        }
        return any(self._runs(prefix) for prefix in holders)

    def get_node_names(self) -> list[str]:
        return [name for name, _namespace in self.get_node_names_and_namespaces()]

    def _require_live_node(self, node_name: str, node_namespace: str) -> None:
        holders, dead = self._liveness()
        held = holders.get(_full_name(node_name, node_namespace))
        if dead and held and held <= dead:
            raise NodeNameNonExistentError(
                f"node {_full_name(node_name, node_namespace)} has ended"
            )

    def get_publisher_names_and_types_by_node(
        self, node_name: str, node_namespace: str, no_demangle: bool = False
    ) -> list[tuple[str, list[str]]]:
        self._require_live_node(node_name, node_namespace)
        return super().get_publisher_names_and_types_by_node(
            node_name, node_namespace, no_demangle
        )

    def get_subscriber_names_and_types_by_node(
        self, node_name: str, node_namespace: str, no_demangle: bool = False
    ) -> list[tuple[str, list[str]]]:
        self._require_live_node(node_name, node_namespace)
        return super().get_subscriber_names_and_types_by_node(
            node_name, node_namespace, no_demangle
        )

    def get_service_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        self._require_live_node(node_name, node_namespace)
        return super().get_service_names_and_types_by_node(node_name, node_namespace)

    def get_client_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        self._require_live_node(node_name, node_namespace)
        return super().get_client_names_and_types_by_node(node_name, node_namespace)
