"""The calls half of the course's client node: nodes' parameter services, each write sent once
(RosClient composes it with the graph and the journal)."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

from rcl_interfaces.msg import Parameter, ParameterType
from rcl_interfaces.msg import ParameterValue as ParameterValueMsg
from rcl_interfaces.srv import DescribeParameters, GetParameters, ListParameters, SetParameters

from ...core.waiting import wait_until
from ..results import Descriptor, ParamRange, SetResult
from ..values import VALUE_FIELDS, ParamValue, value_from_msg

__all__ = [
    "CALL_TIMEOUT_S",
    "SERVICE_WAIT_S",
    "ParamCalls",
    "ServiceCallError",
    "value_to_msg",
]

SERVICE_WAIT_S = 5.0
CALL_TIMEOUT_S = 10.0
# First wait for a reply before re-sending a read (a reply normally takes about 1 ms).
FIRST_ATTEMPT_S = 0.5
# Services whose requests change the node: sent exactly once, after a probe (see _call).
_WRITES = {"set_parameters": SetParameters.Request}
_SERVICES = {
    "list_parameters": ListParameters,
    "get_parameters": GetParameters,
    "set_parameters": SetParameters,
    "describe_parameters": DescribeParameters,
}


class ServiceCallError(RuntimeError):
    """A parameter service did not answer (ros2cli prints the message and exits 1)."""

    @property
    def cli_message(self) -> str:
        return str(self)


def value_to_msg(value: ParamValue) -> ParameterValueMsg:
    """Convert a ParamValue into an rcl_interfaces ParameterValue."""
    msg = ParameterValueMsg(type=value.type)
    field = VALUE_FIELDS.get(value.type)
    if field is not None:
        raw = value.value
        setattr(msg, field, list(raw) if value.type >= ParameterType.PARAMETER_BYTE_ARRAY else raw)
    return msg


def _descriptor(msg: Any) -> Descriptor:
    ranges = tuple(
        ParamRange(r.from_value, r.to_value, r.step)
        for r in [*msg.floating_point_range, *msg.integer_range]
    )
    return Descriptor(
        name=msg.name,
        type=msg.type,
        description=msg.description,
        additional_constraints=msg.additional_constraints,
        read_only=msg.read_only,
        dynamic_typing=msg.dynamic_typing,
        ranges=ranges,
    )


class ParamCalls:
    """Requests to nodes' parameter services over one long-lived rclpy node (thread-safe)."""

    def __init__(self, node: Any, wait_future: Callable[[Any, float], Any]) -> None:
        self.node = node
        self._wait_future = wait_future
        self._clients: dict[tuple[str, str], Any] = {}
        # Per client: the server reply writers whose path to our reply reader a probe proved.
        self._proven: dict[tuple[str, str], frozenset[bytes]] = {}
        self._lock = threading.Lock()

    def _client(self, node_name: str, service: str) -> Any:
        key = (node_name, service)
        with self._lock:
            if key not in self._clients:
                self._clients[key] = self.node.create_client(
                    _SERVICES[service], f"{node_name}/{service}"
                )
            return self._clients[key]

    def services_ready(self, node_name: str, *, timeout: float = SERVICE_WAIT_S) -> bool:
        """Wait until the node's parameter services answer requests; False after `timeout`."""
        clients = [self._client(node_name, s) for s in _SERVICES]
        return wait_until(lambda: all(c.service_is_ready() for c in clients), timeout)

    def answers(self, node_name: str, *, timeout: float) -> bool:
        """Return whether the node answers a parameter request within `timeout`: a node does
        once it spins, that is once its constructor (which makes its publishers) is done."""
        request = ListParameters.Request(depth=1)
        try:
            self._call(node_name, "list_parameters", request, within=timeout)
        except ServiceCallError:
            return False
        return True

    def _call(
        self,
        node_name: str,
        service: str,
        request: Any,
        *,
        within: float | None = None,
        writers: frozenset[bytes] | None = None,
    ) -> Any:
        """Call one of the node's parameter services once it is ready; return the response.

        By default the service has SERVICE_WAIT_S to be ready, then CALL_TIMEOUT_S to answer;
        `within` bounds both together (ServiceCallError once it has passed). `writers`: the
        service's reply writers (`reply_writers`), when the caller has just looked them up.
        """
        started = time.monotonic()
        client = self._client(node_name, service)
        if not wait_until(client.service_is_ready, SERVICE_WAIT_S if within is None else within):
            raise ServiceCallError(
                f"Wait for service timed out waiting for parameter services for node {node_name}"
            )
        deadline = time.monotonic() + CALL_TIMEOUT_S if within is None else started + within
        if service not in _WRITES:
            return self._call_with_retries(client, node_name, request, deadline)
        # Fast DDS's server waits only 100 ms for our reply reader to match before it drops a
        # reply, and a freshly created client (or a restarted node) is "ready" as soon as we
        # know the server, before the server knows our reader. An empty request changes
        # nothing and may be repeated: once one is answered, the reply path exists and the
        # write is sent exactly once (a re-sent write would apply twice). The proof holds
        # until the server's reply writer changes (a restarted node); unknown writers: probe.
        key = (node_name, service)
        if writers is None:
            writers = self.reply_writers(node_name, service)
        if not writers or self._proven.get(key) != writers:
            self._call_with_retries(client, node_name, _WRITES[service](), deadline)
            self._proven[key] = writers
        return self._call_once(client, node_name, request, deadline)

    def reply_writers(self, node_name: str, service: str = "set_parameters") -> frozenset[bytes]:
        """Return the GIDs of the service's reply writers, as the local graph knows them.

        ROS 2 maps a service's replies to the DDS topic `rr/<service>Reply`; an RMW that
        names it otherwise yields nothing here, and every write is then probed first.
        """
        topic = f"rr{node_name}/{service}Reply"
        try:
            infos = self.node.get_publishers_info_by_topic(topic, no_mangle=True)
        except Exception:  # an RMW without this graph query: probe every write
            return frozenset()
        return frozenset(bytes(info.endpoint_gid) for info in infos)

    def _timed_out(self, node_name: str) -> ServiceCallError:
        return ServiceCallError(
            f"Exception while calling service of node '{node_name}': "
            f"no answer within {CALL_TIMEOUT_S:g} s"
        )

    def _call_once(self, client: Any, node_name: str, request: Any, deadline: float) -> Any:
        future = client.call_async(request)
        try:
            return self._wait_future(future, max(deadline - time.monotonic(), 0.01))
        except TimeoutError:
            client.remove_pending_request(future)
            raise self._timed_out(node_name) from None

    def _call_with_retries(
        self, client: Any, node_name: str, request: Any, deadline: float
    ) -> Any:
        """Send a request that changes nothing, re-sending with a doubling timeout."""
        attempt_s = FIRST_ATTEMPT_S
        while True:
            future = client.call_async(request)
            remaining = deadline - time.monotonic()
            try:
                return self._wait_future(future, min(attempt_s, max(remaining, 0.01)))
            except TimeoutError:
                client.remove_pending_request(future)
                if time.monotonic() >= deadline:
                    raise self._timed_out(node_name) from None
                attempt_s *= 2

    def list_parameters(self, node_name: str, prefixes: Sequence[str] = ()) -> list[str]:
        """Return the names of the node's parameters (optionally under `prefixes`)."""
        request = ListParameters.Request(prefixes=list(prefixes), depth=0)
        return list(self._call(node_name, "list_parameters", request).result.names)

    def get_parameters(self, node_name: str, names: Sequence[str]) -> list[ParamValue]:
        """Return the values of `names` (an unknown name yields no value or NOT_SET)."""
        response = self._call(node_name, "get_parameters", GetParameters.Request(names=names))
        return [value_from_msg(v) for v in response.values]

    def set_parameters(
        self,
        node_name: str,
        values: Sequence[tuple[str, ParamValue]],
        *,
        writers: frozenset[bytes] | None = None,
    ) -> list[SetResult]:
        """Set each parameter on its own (not atomically); return one result per parameter.

        `writers`: the service's reply writers, if the caller has just looked them up.
        """
        params = [Parameter(name=n, value=value_to_msg(v)) for n, v in values]
        request = SetParameters.Request(parameters=params)
        response = self._call(node_name, "set_parameters", request, writers=writers)
        return [
            SetResult(r.successful, r.reason, name)
            for r, (name, _v) in zip(response.results, values, strict=False)
        ]

    def describe_parameters(self, node_name: str, names: Sequence[str]) -> list[Descriptor]:
        """Return the descriptors of `names`."""
        request = DescribeParameters.Request(names=list(names))
        response = self._call(node_name, "describe_parameters", request)
        return [_descriptor(d) for d in response.descriptors]

    def close(self) -> None:
        """Destroy the cached service clients."""
        with self._lock:
            for client in self._clients.values():
                self.node.destroy_client(client)
            self._clients.clear()
            self._proven.clear()
