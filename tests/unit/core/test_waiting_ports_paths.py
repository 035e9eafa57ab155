"""The shared small jobs: waiting on a condition, probing a free port and who holds one,
editing a path list."""

from __future__ import annotations

import os
import socket

import pytest

from course_lib.core.host.ports import free_port, held_only_by
from course_lib.core.paths import append_once, prepend
from course_lib.core.waiting import wait_until


def test_wait_until_returns_the_value_that_held() -> None:
    answers = iter([0, "", "found"])
    assert wait_until(lambda: next(answers), 1.0, interval=0.0) == "found"


def test_wait_until_returns_the_last_false_value_or_raises_with_a_message() -> None:
    assert wait_until(lambda: [], 0.0) == []
    with pytest.raises(TimeoutError, match="never"):
        wait_until(lambda: None, 0.0, message="never")


def test_a_free_port_can_be_bound() -> None:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", free_port()))


def test_a_port_is_held_only_by_the_account_whose_socket_listens_there() -> None:
    me, someone_else = os.getuid(), os.getuid() + 1
    with socket.create_server(("127.0.0.1", 0)) as listener:
        port = listener.getsockname()[1]
        assert held_only_by("127.0.0.1", port, me)
        assert not held_only_by("127.0.0.1", port, someone_else)
        assert held_only_by("::ffff:127.0.0.1", port, me)  # the same address, mapped
        assert not held_only_by("127.0.0.2", port, me), "another address is another socket"
    assert not held_only_by("127.0.0.1", port, me), "nobody listens there any more"


def test_a_wildcard_listener_takes_loopback_connections_too() -> None:
    with socket.create_server(("", 0), family=socket.AF_INET6, dualstack_ipv6=True) as any_:
        port = any_.getsockname()[1]
        assert held_only_by("127.0.0.1", port, os.getuid())
        assert not held_only_by("127.0.0.1", port, os.getuid() + 1)
        assert held_only_by("::1", port, os.getuid())


def test_prepend_moves_to_front_and_append_once_keeps_the_callers_order() -> None:
    assert prepend("/b", "/a::/b:/c") == "/b:/a:/c"
    assert prepend("/b", None) == "/b"
    assert append_once("/b", "/b:/a") == "/b:/a"
    assert append_once("/b", "/a:") == "/a:/b"
