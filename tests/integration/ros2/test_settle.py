"""A young client waits until it has met the graph; a warm one answers at once.

The wait's rules are unit-tested on a fake clock (tests/unit/ros2/node/test_ros2_discovery.py).
"""

from __future__ import annotations

import signal
import socket
import sys
import time

import pytest

from course_lib.core.host import procfs
from course_lib.core.waiting import wait_until
from course_lib.processes.children import spawn
from course_lib.ros2.node.client import RosClient
from course_lib.ros2.node.discovery import FASTDDS_DEFAULT_ANNOUNCEMENT_S
from course_lib.ros2.node.participants import read_bound_participants
from course_lib.session.session import Session

pytestmark = pytest.mark.ros


def _young_client(domain_id: int | None = None) -> tuple[Session, RosClient]:
    session = Session(domain_id=domain_id)
    return session, RosClient(session.node, session.wait_future)


def test_settled_graph_shows_a_node_started_before_the_client(session: Session) -> None:
    child = session.run("parameter_tests", "param_vel")
    owner = RosClient(session.node, session.wait_future)
    try:
        assert wait_until(lambda: "/param_vel_node" in _names(owner), 10)
        late, client = _young_client(session.domain_id)
        try:
            client.settle()
            assert "/param_vel_node" in _names(client)
        finally:
            late.close()
    finally:
        child.stop()


def test_a_warm_client_does_not_wait() -> None:
    # A domain of its own: in the module's domain a node stopped by another test can stay in
    # this long-lived node's graph as a ghost (ros2/ros2#1413), which a client that never
    # listed it waits GHOST_GRACE_S for (a new node's name also comes before its endpoints):
    # on a busy host the CI saw that second here, three times of three.
    own, client = _young_client()
    try:
        client.graph._born -= 2 * FASTDDS_DEFAULT_ANNOUNCEMENT_S  # as old as a warm daemon's
        started = time.monotonic()
        client.settle()
        # a young client waits for the announcement period (seconds); a warm one only asks
        # the graph once (milliseconds; bounded loosely, so a busy machine never fails it)
        assert time.monotonic() - started < 0.5
    finally:
        own.close()


def _names(client: RosClient) -> set[str]:
    return {n.full_name for n in client.node_names()}


def test_two_live_namesakes_are_both_listed() -> None:
    """The ghost filter (discovery.without_ghosts) never hides a real duplicate: two live
    param_vel_node processes are listed twice, as the real `ros2 node list` does. In a domain
    of its own: a ghost left by another test's node (ros2/ros2#1413) plus one namesake also
    count two while the graph is not settled (the filter waits for a settled graph)."""
    own, client = _young_client()
    first = own.run("parameter_tests", "param_vel")
    second = own.run("parameter_tests", "param_vel")
    try:

        def twice() -> bool:
            names = [n.full_name for n in client.node_names()]
            return names.count("/param_vel_node") == 2

        def settled() -> bool:
            return client.graph._holders()[1]

        # settled first: every bound participant seen, so the filter did run
        assert wait_until(lambda: settled() and twice(), 15), (
            [n.full_name for n in client.node_names()],
            settled(),
        )
    finally:
        first.stop()
        second.stop()
        own.close()


def test_a_fresh_client_finds_a_node_whose_process_is_slow_to_answer(session: Session) -> None:
    """A node's process starved on a busy host answers a fresh client's discovery late (two
    busy loops on 2 cores: a restarted kernel's `lesson.reset()` said "Node not found ...
    running nodes: none" while the node ran). Here the process is stopped for 6 s: its sockets
    are bound, so the client knows a participant is unseen, and waits for it."""
    import os
    import threading

    child = session.run("parameter_tests", "param_vel")
    owner = RosClient(session.node, session.wait_future)
    try:
        assert wait_until(lambda: "/param_vel_node" in _names(owner), 10)
        os.kill(child.pid, signal.SIGSTOP)
        resume = threading.Timer(6.0, os.kill, args=(child.pid, signal.SIGCONT))
        late, client = _young_client(session.domain_id)
        try:
            started = time.monotonic()
            resume.start()
            found = client.wait_for_node("/param_vel_node", include_hidden=False, timeout=0)
            took = time.monotonic() - started
            assert found, f"not found after {took:.1f} s"
            assert took >= 5.0  # found once the process ran again, not before
        finally:
            resume.cancel()
            os.kill(child.pid, signal.SIGCONT)
            late.close()
    finally:
        child.stop()


# A node of its own process (its pid is its participant's), printing once it is up.
PLAIN_NODE = (
    "import rclpy; rclpy.init(); node = rclpy.create_node('leaving_node'); "
    "print('up', flush=True); rclpy.spin(node)"
)


def _hold_participant_port(domain_id: int) -> socket.socket:
    """Bind a free participant port of the domain: bound on this host, never seen in DDS."""
    base = 7400 + 250 * domain_id
    for index in range(119, 0, -1):  # the last participant ports first
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            sock.bind(("0.0.0.0", base + 10 + 2 * index))
            return sock
        except OSError:
            sock.close()
    raise AssertionError(f"no free participant port in domain {domain_id}")


@pytest.mark.parametrize("reaped", [True, False], ids=["reaped", "not-reaped-yet"])
def test_a_participant_that_has_left_does_not_stand_in_for_one_not_seen(reaped: bool) -> None:
    """A client still sees a killed process's participant until its lease ends; meanwhile it
    must not count it for one bound on this host but not seen yet (here a held port). Until its
    parent reaps it, the killed process is still listed, its ports free (run 23 of stop 46)."""
    own, client = _young_client()
    unseen = _hold_participant_port(own.domain_id)
    # without its output read, a child is reaped only when waited for (it dies with the test)
    leaving = spawn([sys.executable, "-c", PLAIN_NODE], name="leaving", env=own.env, capture=False)
    try:
        assert wait_until(lambda: "/leaving_node" in _names(client), 30)
        assert wait_until(lambda: client.graph_view().missing_participants == 1, 10)
        bound = read_bound_participants(own.domain_id)
        leaving.send_signal(signal.SIGKILL, reason="a participant that leaves without a word")
        if reaped:
            leaving.wait()
        assert wait_until(lambda: read_bound_participants(own.domain_id) == bound - 1, 5)
        assert reaped or procfs.stat_fields(leaving.pid)[0] == "Z"  # type: ignore[index]
        view = client.graph_view()
        assert leaving.pid & 0xFFFF in view.participant_pids, "its lease ended already"
        assert view.missing_participants == 1, view
    finally:
        leaving.stop()
        unseen.close()
        own.close()


def test_a_joining_node_is_asked_to_answer_only_if_it_has_parameter_services(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A command waits until a node starting now answers a parameter request (its constructor,
    which makes its publishers, is done). A node made without parameter services never
    answers: it is left to the graph's quiet (it held every command for NEWCOMER_S)."""
    from ros2_golden import GOLDEN

    own, client = _young_client()
    plain = own.spawn([sys.executable, str(GOLDEN / "nodes" / "param_vel_node.py")], name="a")
    bare = own.spawn(
        [sys.executable, str(GOLDEN / "nodes" / "no_param_services_node.py")], name="b"
    )
    try:
        for name in ("/param_vel_node", "/no_param_services_node"):
            assert client.wait_for_node(name, include_hidden=False, timeout=15)
        assert client.services_ready("/param_vel_node", timeout=15)
        assert client.wait_all_seen(15)  # every endpoint named: as wait_joined asks
        asked: list[str] = []
        monkeypatch.setattr(client, "answers", lambda name, timeout: asked.append(name) or True)
        pids = frozenset(child.pid & 0xFFFF for child in (plain, bare))
        assert client.graph._spinning(pids, 5.0)
        assert asked == ["/param_vel_node"]

        # a node's name seen before its services (they show 0.3 s later): it is asked
        offers, shown = client.graph._offers_parameters, time.monotonic() + 0.3

        def services_late(name: str) -> bool:
            return time.monotonic() >= shown and offers(name)

        monkeypatch.setattr(client.graph, "_offers_parameters", services_late)
        asked.clear()
        assert client.graph._spinning(pids, 5.0)
        assert asked == ["/param_vel_node"]
    finally:
        own.close()
