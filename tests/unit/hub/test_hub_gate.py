"""The hub's gate on loopback: who opened a connection (the kernel says), a connection carried
both ways to the Unix socket behind, one past the limit reset at once, an idle one closed
before it reaches anything."""

from __future__ import annotations

import os
import socket
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.hub.guard import admission, gate
from course_lib.hub.guard.gate import Door, Gate, unix_listener
from course_lib.hub.guard.peers import Peer, PeerFinder


def test_the_kernel_names_the_account_of_a_local_connection_only() -> None:
    finder = PeerFinder()
    server = socket.create_server(("::", 0), family=socket.AF_INET6, dualstack_ipv6=True)
    with server, socket.create_connection(("127.0.0.1", server.getsockname()[1])):
        accepted, _ = server.accept()  # ::ffff:127.0.0.1 on a dual-stack socket
        with accepted:
            assert finder.peer(accepted) == Peer(uid=os.geteuid())
            port = server.getsockname()[1]
            assert finder.uid_of("192.0.2.7", 40000, "127.0.0.1", port) is None  # not here
    finder.close()


def _echo(listener: socket.socket, accepted: list[socket.socket]) -> None:
    while True:
        try:
            connection, _ = listener.accept()
        except OSError:
            return
        accepted.append(connection)
        with connection:
            while data := connection.recv(65536):
                connection.sendall(data)


@pytest.fixture
def door(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[tuple[int, list]]:
    """Yield the port of a gate (2 connections per account) to an echo server, and the
    connections the echo server took."""
    monkeypatch.setattr(gate, "FIRST_BYTES_S", 0.3)
    monkeypatch.setattr(admission, "UNLIMITED", Peer(uid=-1))  # root too, as the tests run
    behind, accepted = unix_listener(str(tmp_path / "echo.sock")), []
    threading.Thread(target=_echo, args=(behind, accepted), daemon=True).start()
    listener = socket.create_server(("127.0.0.1", 0))
    lines: list[str] = []
    served = Gate([Door(listener, str(tmp_path / "echo.sock"), "door")], per_peer=2,
                  log=lines.append)  # fmt: skip
    served.start()
    try:
        yield listener.getsockname()[1], accepted
    finally:
        served.stop()
        listener.close()
        behind.close()
    assert lines == []  # reports come every 10 s


def test_a_connection_is_carried_both_ways(door: tuple[int, list]) -> None:
    port, _ = door
    with socket.create_connection(("127.0.0.1", port), timeout=5) as client:
        client.sendall(b"GET / HTTP/1.1\r\n\r\n")
        assert client.recv(100) == b"GET / HTTP/1.1\r\n\r\n"


def test_a_connection_past_the_accounts_limit_is_reset(door: tuple[int, list]) -> None:
    port, _ = door
    held = [socket.create_connection(("127.0.0.1", port), timeout=5) for _ in range(2)]
    try:
        # reset at once: seen by the connect itself when the gate is quick (ci), else by recv
        with (
            pytest.raises(ConnectionResetError),
            socket.create_connection(("127.0.0.1", port), timeout=5) as third,
        ):
            third.recv(1)
    finally:
        for client in held:
            client.close()


def test_an_idle_connection_is_closed_before_it_reaches_anything(
    door: tuple[int, list],
) -> None:
    port, accepted = door
    with socket.create_connection(("127.0.0.1", port), timeout=5) as idle:
        assert idle.recv(1) == b""  # closed after FIRST_BYTES_S
    assert accepted == []
