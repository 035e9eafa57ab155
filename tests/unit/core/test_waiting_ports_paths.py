"""The shared small jobs: waiting on a condition, probing a free port, editing a path list."""

from __future__ import annotations

import socket

import pytest

from course_lib.core.paths import append_once, prepend
from course_lib.core.ports import free_port
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


def test_prepend_moves_to_front_and_append_once_keeps_the_callers_order() -> None:
    assert prepend("/b", "/a::/b:/c") == "/b:/a:/c"
    assert prepend("/b", None) == "/b"
    assert append_once("/b", "/b:/a") == "/b:/a"
    assert append_once("/b", "/a:") == "/a:/b"
