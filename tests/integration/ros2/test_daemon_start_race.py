"""Commands that find no daemon at the same moment start one daemon between them.

Run 40 of stop 43: four racing first calls each started a daemon; the three that lost were
still starting when the winner was stopped, and one of them became a daemon nobody asked for
(test_ros2_first_call then failed every rerun). Starting now takes turns on a lock file.
"""

from __future__ import annotations

import threading

import pytest

from course_lib.core.waiting import wait_until
from course_lib.ros2.node import connect

pytestmark = [
    pytest.mark.ros,
    # the daemon outlives its Popen on purpose (spawn_detached): Python warns at collection
    pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning"),
]


def _terminal_first_call(env: dict[str, str]) -> bool:
    """What a terminal's `ros2` does (command.cli): connect, starting the daemon if need be."""
    connect.connect_or_start(env["ROS_DOMAIN_ID"], env).close()
    return True


@pytest.mark.parametrize(
    "first_call",
    [connect.start_detached, _terminal_first_call],
    ids=["ros2-daemon-start", "any-command"],
)
def test_racing_starts_spawn_one_daemon(leased_env, monkeypatch, first_call) -> None:  # type: ignore[no-untyped-def]
    spawned: list[int] = []
    real_spawn = connect.spawn_detached

    def counting_spawn(env) -> None:  # type: ignore[no-untyped-def]
        spawned.append(1)
        real_spawn(env)

    monkeypatch.setattr(connect, "spawn_detached", counting_spawn)
    gate = threading.Barrier(4)
    started: list[bool] = []

    def racer() -> None:
        gate.wait()
        started.append(first_call(leased_env))

    threads = [threading.Thread(target=racer) for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(30)
    assert len(spawned) == 1, f"{len(spawned)} daemons started for one domain"
    if first_call is connect.start_detached:  # says whether it started the daemon
        assert sorted(started) == [False, False, False, True]
    else:
        assert started == [True] * 4  # every command got its connection
    domain = leased_env["ROS_DOMAIN_ID"]
    assert wait_until(lambda: len(connect.daemon_pids(domain)) == 1, 10)
