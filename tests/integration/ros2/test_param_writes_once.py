"""A parameter write reaches the node exactly once, even on a freshly matched service."""

from __future__ import annotations

import sys
import textwrap
import threading
import time
from collections.abc import Iterator

import pytest
from rcl_interfaces.msg import ParameterEvent
from rclpy.qos import qos_profile_parameter_events

from course_lib.core.waiting import wait_until
from course_lib.ros2.node.client import RosClient
from course_lib.ros2.values import ParamValue
from course_lib.session.session import Session

pytestmark = pytest.mark.ros

# A node that prints each set it accepts, after `delay` seconds. At 0.8 s (a node that acts
# on it) it answers later than the client's first wait for a read's reply, so a client that
# re-sent writes would apply this one twice.
ACCEPTING_NODE = textwrap.dedent(
    """
    import sys
    import time
    import rclpy
    from rcl_interfaces.msg import SetParametersResult

    name, delay = sys.argv[1], float(sys.argv[2])
    rclpy.init()
    node = rclpy.create_node(name)
    node.declare_parameter("velocity", 0.0)

    def accept(parameters):
        time.sleep(delay)
        print("accepted", [p.value for p in parameters], flush=True)
        return SetParametersResult(successful=True)

    node.add_on_set_parameters_callback(accept)
    rclpy.spin(node)
    """
)


def _accepting_node(session: Session, name: str, delay: float):  # type: ignore[no-untyped-def]
    argv = [sys.executable, "-c", ACCEPTING_NODE, name, str(delay)]
    return session.spawn(argv, name=name)


def _accepted(child) -> list[str]:  # type: ignore[no-untyped-def]
    return [line.text for line in child.lines if line.text.startswith("accepted")]


class Events:
    """Collect the /parameter_events changes of one node: (name, double value)."""

    def __init__(self, session: Session, node: str) -> None:
        self.node, self.changes = node, []
        self._lock = threading.Lock()
        self._session = session
        self._sub = session.node.create_subscription(
            ParameterEvent, "/parameter_events", self._on_event, qos_profile_parameter_events
        )

    def _on_event(self, msg: ParameterEvent) -> None:
        if msg.node == self.node:
            with self._lock:
                self.changes += [(p.name, p.value.double_value) for p in msg.changed_parameters]

    def settled(self, count: int, quiet_s: float = 0.5) -> list[tuple[str, float]]:
        """Wait until `count` changes came (or none for `quiet_s` more), then return them."""
        wait_until(lambda: len(self.changes) >= count, 10)
        time.sleep(quiet_s)  # a duplicate would arrive within this
        return list(self.changes)

    def close(self) -> None:
        self._session.node.destroy_subscription(self._sub)


@pytest.fixture
def param_vel(session: Session) -> Iterator[str]:
    """Start a fresh tutorial node; yield its name once the graph shows its services."""
    child = session.run("parameter_tests", "param_vel", "--ros-args", "-r", "__node:=once_node")
    ready = RosClient(session.node, session.wait_future)
    assert ready.services_ready("/once_node", timeout=15), "/once_node never answered"
    ready.close()
    yield "/once_node"
    child.stop()


def test_200_sets_each_make_exactly_one_event(session: Session, param_vel: str) -> None:
    events = Events(session, param_vel)
    client = RosClient(session.node, session.wait_future)
    try:
        values = [round(0.001 * i, 3) for i in range(1, 201)]
        for value in values:
            (result,) = client.set_parameters(param_vel, [("velocity", ParamValue.of(value))])
            assert result.successful, result.reason
        assert events.settled(200) == [("velocity", v) for v in values]
    finally:
        client.close()
        events.close()


def test_first_set_of_a_fresh_client_answers_within_bound(
    session: Session, param_vel: str
) -> None:
    """Each new client's reply path is freshly matched (where Fast DDS drops first replies)."""
    events = Events(session, param_vel)
    try:
        values = [round(0.5 + 0.01 * i, 2) for i in range(20)]
        for value in values:
            client = RosClient(session.node, session.wait_future)
            started = time.monotonic()
            (result,) = client.set_parameters(param_vel, [("velocity", ParamValue.of(value))])
            took = time.monotonic() - started
            client.close()
            assert result.successful and took < 2.0, (value, took)
        assert events.settled(20) == [("velocity", v) for v in values]
    finally:
        events.close()


def test_a_slow_node_gets_the_write_once(session: Session) -> None:
    child = _accepting_node(session, "slow_node", delay=0.8)
    events = Events(session, "/slow_node")
    client = RosClient(session.node, session.wait_future)
    try:
        assert client.wait_for_node("/slow_node", include_hidden=False, timeout=10)
        (result,) = client.set_parameters("/slow_node", [("velocity", ParamValue.of(0.3))])
        assert result.successful
        assert events.settled(1, quiet_s=2.0) == [("velocity", 0.3)]
        assert _accepted(child) == ["accepted [0.3]"]
    finally:
        client.close()
        events.close()
        child.stop()


def test_the_server_reply_writer_is_known(session: Session, param_vel: str) -> None:
    """Tripwire: writes skip the probe once proven for this writer (else each write probes)."""
    client = RosClient(session.node, session.wait_future)
    try:
        assert client.services_ready(param_vel, timeout=10)
        assert len(client.calls.reply_writers(param_vel, "set_parameters")) == 1, (
            "the graph no longer shows the service's reply writer (rr/<service>Reply): every "
            "write now costs a probe round trip"
        )
    finally:
        client.close()


def test_a_restarted_node_gets_each_write_once(session: Session) -> None:
    """A cached client meets a new server (new reply writer): the path is proven again.

    Each node counts the sets it applies itself: its /parameter_events change is volatile, so
    a node that has only just started can send it before it has matched our reader (the
    0.22 event was missed so once, on a busy host).
    """
    client = RosClient(session.node, session.wait_future)
    proofs = []  # the reply writers each write was proven for
    try:
        for value in (0.11, 0.22):
            child = _accepting_node(session, "again_node", delay=0.0)
            try:
                assert client.services_ready("/again_node", timeout=15)
                started = time.monotonic()
                (result,) = client.set_parameters(
                    "/again_node", [("velocity", ParamValue.of(value))]
                )
                assert result.successful and time.monotonic() - started < 2.0
                time.sleep(0.5)  # a write re-sent would be applied within this
                proofs.append(client.calls._proven[("/again_node", "set_parameters")])
            finally:
                child.stop()
            assert _accepted(child) == [f"accepted [{value}]"]
            assert wait_until(lambda: not client.services_ready("/again_node", timeout=0), 10)
        assert proofs[0] and proofs[1] and not proofs[0] & proofs[1], (
            "the restarted node's reply path was not proven again",
            proofs,
        )
    finally:
        client.close()
