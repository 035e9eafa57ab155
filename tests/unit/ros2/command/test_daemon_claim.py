"""A daemon's socket path exists only once the daemon listens on it.

Clients and tests take the path's presence as "the daemon is ready"; a connection made
between bind and listen is refused (a test that waited for the path met it in CI).
"""

from __future__ import annotations

import os
import socket
from collections.abc import Iterator

import pytest

from course_lib.processes.domain import lease_domain
from course_lib.ros2.command import daemon
from course_lib.ros2.node.wire import connect, daemon_socket


@pytest.fixture(params=[False, True], ids=["fresh", "over-a-killed-daemons-socket"])
def claimed(
    monkeypatch: pytest.MonkeyPatch, request: pytest.FixtureRequest
) -> Iterator[tuple[str, list[bool]]]:
    """Claim a leased domain's socket in this process (over a killed daemon's leftover
    socket, or not); yield its path and, for each listen(), whether a socket of its own
    was at the path then."""
    lease = lease_domain({})
    path = daemon_socket(lease.domain_id)
    at_listen: list[bool] = []
    opened: list[int] = []
    real_open = os.open

    class Recording(socket.socket):
        def listen(self, *args: int) -> None:
            at_listen.append(os.path.exists(path) and os.stat(path).st_ino != leftover_ino)
            super().listen(*args)

    def recording_open(*args, **kwargs) -> int:  # type: ignore[no-untyped-def]
        opened.append(real_open(*args, **kwargs))  # the lock _claim keeps for life
        return opened[-1]

    leftover_ino = None
    if os.path.lexists(path):  # a daemon killed earlier on this machine left it: not "fresh"
        os.unlink(path)  # the domain is leased to this test, so no daemon of it runs
    if request.param:
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as killed:
            killed.bind(path)  # a killed daemon's socket, left behind, answering nobody
        leftover_ino = os.stat(path).st_ino
    monkeypatch.setattr(daemon.socket, "socket", Recording)
    monkeypatch.setattr(daemon.os, "open", recording_open)
    server = daemon._claim(lease.domain_id)
    monkeypatch.undo()
    try:
        assert server is not None
        yield path, at_listen
    finally:
        if server is not None:
            server.close()
        for fd in opened:
            os.close(fd)
        for leftover in (path, path + daemon.STAGING_SUFFIX):
            if os.path.lexists(leftover):
                os.unlink(leftover)
        lease.release()


def test_the_path_appears_only_once_the_socket_listens(claimed: tuple[str, list[bool]]) -> None:
    path, at_listen = claimed
    assert at_listen == [False]
    connect(path).close()  # a socket that accepts (a leftover was replaced)
    assert not os.path.lexists(path + daemon.STAGING_SUFFIX)
