"""How long a fresh client waits for discovery (pure: a fake clock and a scripted graph)."""

from __future__ import annotations

import argparse
from dataclasses import replace

import pytest
from fake_clock import FakeClock

from course_lib.core.host.procfs import udp_ports
from course_lib.core.paths import PACKAGE_DIR
from course_lib.ros2.command import parsers
from course_lib.ros2.node.discovery import (
    DEFAULT_TIMING,
    NAME_WAIT_S,
    DiscoveryTiming,
    GraphView,
    profile_timing,
    requested_spin_time,
    timing_from_profile,
    wait_settled,
)
from course_lib.ros2.node.participants import NEWCOMER_S, bound_participants, participant_prefix

PROFILE = PACKAGE_DIR / "dds" / "fastdds_profile.xml"
TIMING = DiscoveryTiming(floor_s=0.35, quiet_s=0.1, unknown_wait_s=3.5)
EMPTY = GraphView(frozenset(), frozenset())
NODE = GraphView(frozenset({"/param_vel_node"}), frozenset({"/cmd_vel"}))
HALF_KNOWN = GraphView(frozenset(), frozenset({"/cmd_vel"}), unknown_endpoints=3)


def test_course_profile_gives_its_announcement_period_plus_endpoint_exchange() -> None:
    timing = profile_timing(PROFILE)
    assert timing == DiscoveryTiming(floor_s=1.1, quiet_s=0.1, unknown_wait_s=3.5)
    assert timing.warm_s == pytest.approx(1.2)


def test_fast_dds_defaults_when_no_profile_or_an_unreadable_one(tmp_path) -> None:  # type: ignore[no-untyped-def]
    assert DEFAULT_TIMING.floor_s == pytest.approx(3.1)
    bad = tmp_path / "bad.xml"
    bad.write_text("<profiles><participant>")
    assert profile_timing(bad) == DEFAULT_TIMING
    assert profile_timing(tmp_path / "missing.xml") == DEFAULT_TIMING
    period = "<leaseAnnouncement><sec>1</sec><nanosec>0</nanosec></leaseAnnouncement>"
    assert period in PROFILE.read_text()
    faster = PROFILE.read_text().replace(
        period, period.replace("1</sec><nanosec>0", "0</sec><nanosec>250000000")
    )
    assert timing_from_profile(faster).floor_s == pytest.approx(0.35)


class Graph(FakeClock):
    """A scripted graph on a fake clock: `views` maps a time to what is seen from then on."""

    def __init__(self, views: dict[float, GraphView]) -> None:
        super().__init__()
        self.views = sorted(views.items())

    def view(self) -> GraphView:
        return [v for t, v in self.views if t <= self.now + 1e-9][-1]

    def settle(
        self,
        *,
        born: float,
        min_age_s: float = 0.0,
        start: float = 0.0,
        starting: object = None,
        spinning: object = None,
    ) -> GraphView:
        self.now = start
        return wait_settled(
            self.view,
            born=born,
            timing=TIMING,
            min_age_s=min_age_s,
            clock=self.clock,
            sleep=self.sleep,
            starting=starting,  # type: ignore[arg-type]
            spinning=spinning,  # type: ignore[arg-type]
        )


def test_a_fresh_client_waits_for_the_node_announced_late() -> None:
    graph = Graph({0.0: EMPTY, 0.3: NODE})
    assert graph.settle(born=0.0) == NODE
    assert 0.35 <= graph.now <= 0.45


def test_a_fresh_client_with_an_empty_graph_answers_at_its_floor() -> None:
    graph = Graph({0.0: EMPTY})
    assert graph.settle(born=0.0) == EMPTY
    assert graph.now == pytest.approx(0.35, abs=0.02)


def test_a_warm_client_answers_at_once() -> None:
    graph = Graph({0.0: NODE})
    assert graph.settle(born=-60.0) == NODE
    assert graph.now == 0.0


def test_a_node_known_by_its_endpoints_only_is_waited_for_bounded() -> None:
    graph = Graph({0.0: HALF_KNOWN, 2.0: NODE})
    assert graph.settle(born=-60.0) == NODE  # even a warm client waits for its name
    assert 2.0 <= graph.now <= 2.1
    late = Graph({0.0: HALF_KNOWN, 5.0: NODE})  # a loaded machine: the name comes late
    assert late.settle(born=0.0) == NODE
    assert late.now == pytest.approx(5.0, abs=0.1)
    stuck = Graph({0.0: HALF_KNOWN})
    assert stuck.settle(born=0.0) == HALF_KNOWN
    assert stuck.now == pytest.approx(NAME_WAIT_S, abs=0.02)


def test_spin_time_is_a_minimum_age() -> None:
    graph = Graph({0.0: NODE})
    graph.settle(born=0.0, min_age_s=1.5)
    assert graph.now == pytest.approx(1.5, abs=0.02)
    graph.settle(born=-60.0, min_age_s=1.5)  # a warm daemon ignores it, as ros2cli's does
    assert graph.now == 0.0


def test_spin_time_typed_or_left_at_its_default() -> None:
    def spin(argv: list[str]) -> float:
        args, _parser = parsers.parse(["node", "list", *argv])
        assert args is not None
        return requested_spin_time(args)

    token = parsers.output_sink.set(parsers._Sink())
    try:
        assert spin([]) == 0.0
        assert spin(["--spin-time", "0.5"]) == 0.5
        assert spin(["--spin-time", "2"]) == 2.0
    finally:
        parsers.output_sink.reset(token)
    assert requested_spin_time(argparse.Namespace()) == 0.0


UDP = """  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid
   0: 00000000:6A18 00000000:0000 07 00000000:00000000 00:00000000 00000000     0
   1: 00000000:6A19 00000000:0000 07 00000000:00000000 00:00000000 00000000     0
   2: 00000000:6A1A 00000000:0000 07 00000000:00000000 00:00000000 00000000     0
   3: 00000000:6A1B 00000000:0000 07 00000000:00000000 00:00000000 00000000     0
   4: 00000000:6A0E 00000000:0000 07 00000000:00000000 00:00000000 00000000     0
   5: 00000000:1CE8 00000000:0000 07 00000000:00000000 00:00000000 00000000     0
"""


def test_participants_are_counted_by_their_metatraffic_ports() -> None:
    # 0x6A18 = 27160 = 7400 + 250 * 79 + 10: participants 0 and 1 of domain 79 (metatraffic
    # and user ports); 0x6A0E is domain 79's multicast port, 0x1CE8 domain 0's.
    assert bound_participants(79, udp_ports([UDP])) == 2
    assert bound_participants(79, udp_ports([UDP, UDP])) == 2
    assert bound_participants(78, udp_ports([UDP])) == 0
    assert participant_prefix(list(range(16))) == tuple(range(12))


def test_a_counting_client_answers_once_it_met_every_participant() -> None:
    graph = Graph(
        {0.0: replace(EMPTY, missing_participants=1), 0.6: replace(NODE, missing_participants=0)}
    )
    assert graph.settle(born=0.0).nodes == NODE.nodes
    assert 0.6 <= graph.now <= 0.72  # past the time-based floor: it waited for the node
    alone = Graph({0.0: replace(EMPTY, missing_participants=0)})
    alone.settle(born=0.0)
    assert alone.now == pytest.approx(0.1, abs=0.02)  # nothing else runs: quiet is enough


def test_a_young_client_answers_only_from_a_view_that_held_still() -> None:
    """A view taken while participants come and go can count them all with the node not seen
    (here: one that has just left still counted for a moment). Four first calls at once, one
    listed only its own topics; a young client now answers only from a view that held still."""
    graph = Graph(
        {
            0.0: replace(EMPTY, missing_participants=1, endpoints=2),
            0.15: replace(EMPTY, missing_participants=0, endpoints=4),  # the ghost's moment
            0.19: replace(EMPTY, missing_participants=1, endpoints=2),  # its endpoints leave
            0.4: replace(NODE, missing_participants=0, endpoints=5),
        }
    )
    assert graph.settle(born=0.0).nodes == NODE.nodes
    assert 0.5 <= graph.now <= 0.52


def test_an_unseen_participant_holds_only_a_young_client_and_bounded() -> None:
    stuck = replace(NODE, missing_participants=1)  # e.g. a suspended process
    young = Graph({0.0: stuck})
    young.settle(born=0.0)
    assert young.now == pytest.approx(3.5, abs=0.02)
    warm = Graph({0.0: stuck})
    warm.settle(born=-60.0)
    assert warm.now == 0.0


def test_a_ghost_of_a_name_listed_twice_is_dropped_once_the_graph_is_settled() -> None:
    from course_lib.ros2.node.discovery import without_ghosts

    names = ["/mujoco", "/param_vel_node", "/param_vel_node", "/param_vel_node"]
    one = {"/mujoco": {(1,)}, "/param_vel_node": {(2,)}}
    assert without_ghosts(names, one, settled=True) == ["/mujoco", "/param_vel_node"]
    two = {"/mujoco": {(1,)}, "/param_vel_node": {(2,), (3,)}}  # two real namesakes stay
    assert without_ghosts(names, two, settled=True) == names[:3]
    # not settled (a participant bound but not seen yet): the graph as it is
    assert without_ghosts(names, one, settled=False) == names


def test_a_name_no_participant_holds_is_dropped_once_listed_for_the_grace() -> None:
    from course_lib.ros2.node.discovery import GHOST_GRACE_S, without_ghosts

    names = ["/mujoco", "/param_vel_node"]
    held = {"/mujoco": {(1,)}}
    old = {"/mujoco": 60.0, "/param_vel_node": GHOST_GRACE_S}
    assert without_ghosts(names, held, settled=True, listed_for=old) == ["/mujoco"]
    # just listed: a new node's endpoints may still follow its name
    new = {**old, "/param_vel_node": GHOST_GRACE_S / 2}
    assert without_ghosts(names, held, settled=True, listed_for=new) == names
    assert without_ghosts(["/a", "/a"], {}, settled=True) == ["/a"]
    # a participant bound on this host not seen yet may hold it
    assert without_ghosts(names, held, settled=False, listed_for=old) == names
    # held: never dropped, however long listed
    both = {**held, "/param_vel_node": {(2,)}}
    assert without_ghosts(names, both, settled=True, listed_for=old) == names


# A node that has just started (pid 4242), as a warm client sees it: its first endpoints
# arrive at 0.6 s, its publisher on /cmd_vel at 0.65 s (one more on a topic already known).
OLD = frozenset({7})
JOINING = {
    0.0: replace(NODE, endpoints=4, participant_pids=OLD),
    0.6: replace(NODE, endpoints=9, participant_pids=OLD | {4242}),
    0.65: replace(NODE, endpoints=10, participant_pids=OLD | {4242}),
}


def test_a_warm_client_waits_for_a_node_that_is_starting_and_counts_all_of_it() -> None:
    graph = Graph(JOINING)
    assert graph.settle(born=-60.0, starting=lambda: frozenset({4242})).endpoints == 10
    assert 1.15 <= graph.now <= 1.2  # its last endpoint, then NEWCOMER_QUIET_S


def test_a_warm_client_waits_until_a_paused_constructor_is_done() -> None:
    """On a busy host a constructor paused 1.2 s between its parameter services and its
    publisher: the graph held still past NEWCOMER_QUIET_S, and `ros2 topic info` moments after
    the node started said "Unknown topic" (ci74). The node says when it is done: it answers a
    request once it spins, after its constructor."""
    paused = {**JOINING, 0.65: JOINING[0.6], 1.85: JOINING[0.65]}  # the publisher at 1.85 s
    graph = Graph(paused)
    asked: list[tuple[frozenset[int], float]] = []

    def spinning(pids: frozenset[int], timeout: float) -> bool:
        asked.append((pids, graph.now))
        graph.sleep(max(0.0, 1.9 - graph.now))  # it answers at 1.9 s, once it spins
        return True

    young = lambda: frozenset({0x10000 + 4242})  # noqa: E731 (a pid past 16 bits)
    assert graph.settle(born=-60.0, starting=young, spinning=spinning).endpoints == 10
    assert [pids for pids, _at in asked] == [frozenset({4242})]  # asked once,
    assert asked[0][1] == pytest.approx(0.6, abs=0.02)  # as soon as it joined
    assert 2.4 <= graph.now <= 2.45  # its answer, then NEWCOMER_QUIET_S
    # without asking it (before): the view of 1.1 s, its publisher missing
    assert Graph(paused).settle(born=-60.0, starting=young).endpoints == 9


def test_a_warm_client_with_no_young_process_answers_at_once() -> None:
    graph = Graph(JOINING)
    assert graph.settle(born=-60.0, starting=frozenset).endpoints == 4
    assert graph.now == 0.0


def test_a_process_that_never_joins_holds_a_warm_client_bounded() -> None:
    graph = Graph({0.0: NODE})
    assert graph.settle(born=-60.0, starting=lambda: frozenset({99})) == NODE
    assert graph.now == pytest.approx(NEWCOMER_S, abs=0.02)
    ages = Graph({0.0: NODE})  # a process that grows old without joining stops the wait
    young = iter([frozenset({99})] * 5 + [frozenset()] * 1000)
    assert ages.settle(born=-60.0, starting=lambda: next(young)) == NODE
    assert ages.now == pytest.approx(0.5, abs=0.05)  # next read of `starting` (10 polls)


def test_a_participant_names_its_process() -> None:
    from course_lib.ros2.node.participants import prefix_pid

    assert prefix_pid([1, 15, 120, 253, 0x99, 0x6A, 151, 51, 0, 0, 0, 0]) == 0x6A99


def test_a_participant_whose_process_has_ended_is_not_counted_as_seen() -> None:
    """Three bound on the host (the client, a command still running, the node not seen yet);
    seen: the client, the command, and one that has ended (its removal not arrived yet)."""
    from course_lib.ros2.node.participants import present_participants, unseen_participants

    def prefix(pid: int) -> tuple[int, ...]:
        return (1, 15, 120, 253, pid & 0xFF, pid >> 8 & 0xFF, 151, 51, 0, 0, 0, 0)

    seen = [prefix(0x1234), prefix(0x2345), prefix(0x3456)]
    running = [0x1234, 0x2345, 0x7777, 0x10000 + 0x0042]  # the node: 0x7777

    def each_runs(pid: int) -> bool:
        return True

    assert present_participants(seen, running, each_runs) == 2  # one missing of 3 bound
    assert present_participants(seen, [*running, 0x3456], each_runs) == 3
    assert present_participants([prefix(0x0042)], running, each_runs) == 1  # low 16 bits
    assert unseen_participants(3, seen, lambda: running, each_runs) == 1  # a count said 0

    def unlisted() -> list[int]:
        raise AssertionError("the processes were listed though the count says one is missing")

    assert unseen_participants(4, seen, unlisted, each_runs) == 1

    # killed, not reaped yet: still listed, but no longer running (its ports are free)
    def zombie_3456(pid: int) -> bool:
        return pid != 0x3456

    assert present_participants(seen, [*running, 0x3456], zombie_3456) == 2
    assert unseen_participants(3, seen, lambda: [*running, 0x3456], zombie_3456) == 1


def test_ros2_commands_are_not_nodes_starting() -> None:
    from course_lib.ros2.node.participants import ros2_client_command

    venv = "/x/.venv/bin"
    assert ros2_client_command((f"{venv}/python", "-S", f"{venv}/ros2", "param", "get", "/n"))
    assert ros2_client_command((f"{venv}/python", f"{venv}/ros2", "topic", "list"))
    assert ros2_client_command(("python", "-P", "-m", "course_lib.ros2.command.cli", "node"))
    script = "import sys; from course_lib.ros2.command.cli import main; sys.exit(main())"
    assert ros2_client_command(("python", "-c", script, "node", "list"))
    assert ros2_client_command((f"{venv}/python", f"{venv}/ros2", "run", "pkg", "exe"))
    launch = ("python", "-m", "course_lib.launch", "--noninteractive", "pkg", "a.launch.py")
    assert ros2_client_command(launch)  # a notebook's %ros2 launch
    assert not ros2_client_command(("python3", "param_vel_node.py"))
    assert not ros2_client_command(("python3", "course_lib.launch"))  # a learner's script
