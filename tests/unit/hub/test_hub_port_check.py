"""The hub's public port check: refused while something listens there, accepted moments after
a hub stopped (its closed connections wait in TIME_WAIT for a minute, and the proxy binds
with SO_REUSEADDR, as the check now does: `make hub` right after a stop said "Address already
in use")."""

from __future__ import annotations

import dataclasses
import socket
from pathlib import Path

import pytest

from course_lib.core.errors import ConfigError
from course_lib.hub.launcher import _check_port
from course_lib.hub.provision.settings import HUB_YAML, load_hub_settings


def _time_wait_on_a_free_port() -> int:
    """Return a port whose listener closed after closing an accepted connection first (the
    listener with SO_REUSEADDR, as Node's, the proxy's, sets it)."""
    with socket.socket() as server:
        server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        server.bind(("127.0.0.1", 0))
        server.listen()
        port = server.getsockname()[1]
        with socket.create_connection(("127.0.0.1", port)) as client:
            accepted, _ = server.accept()
            accepted.close()  # the server side closes first: its end waits in TIME_WAIT
            client.recv(1)
    return port


def test_a_port_left_in_time_wait_by_a_stopped_hub_is_accepted() -> None:
    port = _time_wait_on_a_free_port()
    with socket.socket() as plain, pytest.raises(OSError):  # what the old check did
        plain.bind(("127.0.0.1", port))
    settings = dataclasses.replace(load_hub_settings(HUB_YAML), ip="127.0.0.1", port=port)
    _check_port(settings, Path(HUB_YAML))


def test_a_port_something_listens_on_is_refused() -> None:
    with socket.socket() as listener:
        listener.bind(("127.0.0.1", 0))
        listener.listen()
        port = listener.getsockname()[1]
        settings = dataclasses.replace(load_hub_settings(HUB_YAML), ip="127.0.0.1", port=port)
        with pytest.raises(ConfigError, match=f"port {port} on 127.0.0.1 cannot be used"):
            _check_port(settings, Path(HUB_YAML))
