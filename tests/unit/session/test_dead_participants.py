"""Which seen participants belong to ended processes (`dds_participants.dead_participants`)."""

from __future__ import annotations

from types import SimpleNamespace

from course_lib.session.dds_participants import dead_participants, endpoint_holders, prefix_runs


def _prefix(pid: int) -> tuple[int, ...]:
    return (1, 15, 120, 253, pid & 0xFF, pid >> 8 & 0xFF, 151, 51, 0, 0, 0, 0)


def _runs(pid: int) -> bool:
    return True


CLIENT, NODE, KILLED = 0x1234, 0x2345, 0x3456


def test_a_participant_whose_process_ended_is_dead() -> None:
    seen = [_prefix(CLIENT), _prefix(NODE), _prefix(KILLED)]
    assert dead_participants(seen, 2, [CLIENT, NODE], _runs) == {_prefix(KILLED)}


def test_a_killed_process_not_reaped_yet_is_dead() -> None:
    seen = [_prefix(CLIENT), _prefix(KILLED)]

    def zombie(pid: int) -> bool:
        return pid != KILLED

    assert dead_participants(seen, 1, [CLIENT, KILLED], zombie) == {_prefix(KILLED)}


def test_none_is_dead_while_a_bound_participant_is_not_accounted_for() -> None:
    # a participant of another PID namespace (its pid not shown here) or not seen yet: the
    # unknown pid may be it, so nothing is taken for dead
    seen = [_prefix(CLIENT), _prefix(0x4567)]
    assert dead_participants(seen, 2, [CLIENT], _runs) == frozenset()
    assert dead_participants(seen, 1, [CLIENT], _runs) == {_prefix(0x4567)}


def test_without_proc_none_is_dead() -> None:
    assert dead_participants([_prefix(KILLED)], None, [CLIENT], _runs) == frozenset()


def test_the_low_16_bits_of_a_pid_name_it() -> None:
    assert dead_participants([_prefix(0x0042)], 1, [0x10042], _runs) == frozenset()


def test_endpoint_holders_name_each_node_by_its_participants() -> None:
    def endpoint(namespace: str, name: str, pid: int) -> SimpleNamespace:
        gid = [*_prefix(pid), 0, 0, 1, 3]
        return SimpleNamespace(node_namespace=namespace, node_name=name, endpoint_gid=gid)

    holders = endpoint_holders(
        [
            endpoint("/", "param_vel_node", NODE),
            endpoint("/", "param_vel_node", NODE),
            endpoint("/", "param_vel_node", KILLED),
            endpoint("/robot", "sim", CLIENT),
        ]
    )
    assert holders == {
        "/param_vel_node": {_prefix(NODE), _prefix(KILLED)},
        "/robot/sim": {_prefix(CLIENT)},
    }


def test_a_prefix_runs_if_a_process_with_its_low_pid_bits_runs() -> None:
    """`prefix_runs` asks about the pids a prefix may name (its low 16 bits, below the
    host's pid_max), as `running_participants` does from the list of every process."""
    asked: list[int] = []

    def running(pid: int) -> bool:
        asked.append(pid)
        return pid == NODE + 2 * 65536

    assert prefix_runs(_prefix(NODE), 4 * 65536, running)
    assert asked == [NODE, NODE + 65536, NODE + 2 * 65536]
    assert not prefix_runs(_prefix(KILLED), 4 * 65536, running)
    assert not prefix_runs(_prefix(NODE), NODE, running)  # no pid below pid_max has them
