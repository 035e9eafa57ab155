"""The simulation's faults: meshcat's usual port is taken, and the simulation process dies."""

from __future__ import annotations

import contextlib
import errno
import os
import re
import signal
import socket
import urllib.request
from collections.abc import Iterator

import pytest
from jupyter_kernels import Kernel, describe, process_tree, wait_gone

pytestmark = [pytest.mark.ros, pytest.mark.sim, pytest.mark.slow]

MESHCAT_PORT = 7000  # meshcat-python's default web port

START = """
%load_ext course_lib.notebook.magics
from course_lib.session.session import get_session
from course_lib.notebook import start_world
world = start_world(get_session(), show=True)
print("viewer port", world.viewer.port, "sim pid", world.process.pid)
"""


@pytest.fixture
def port_7000_held() -> Iterator[None]:
    """Hold 127.0.0.1:7000 like another program would (if one already does, keep it so)."""
    holder = socket.socket()
    try:
        holder.bind(("127.0.0.1", MESHCAT_PORT))
        holder.listen()
    except OSError as err:
        assert err.errno == errno.EADDRINUSE, err
    with contextlib.closing(holder):
        yield


def _started(kernel: Kernel) -> tuple[int, int]:
    out = kernel.ok(START, timeout=60)
    found = re.search(r"viewer port (\d+) sim pid (\d+)", out.text)
    assert found, out.everything
    assert "<iframe" in out.html, out.everything
    return int(found[1]), int(found[2])


def test_course_starts_when_meshcat_port_is_taken(start_kernel, port_7000_held) -> None:
    kernel = start_kernel()
    port, _sim = _started(kernel)
    assert port != MESHCAT_PORT
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/static/", timeout=5) as page:
        assert page.status == 200 and b"meshcat" in page.read().lower()
    kernel.ok("assert abs(world.speed()[0]) < 0.01")


def test_dead_simulation_is_reported_and_one_call_restarts_it(start_kernel) -> None:
    kernel = start_kernel()
    _port, sim = _started(kernel)
    os.kill(sim, signal.SIGKILL)
    assert not wait_gone([sim], 5.0)

    after = kernel.run("world.speed()")
    assert "The simulation is not running" in after.error, after.everything
    assert "start_world()" in after.error, "the message should say how to restart"

    again = kernel.ok("world = start_world(show=True)\nprint(world.process.pid)", timeout=60)
    assert int(again.text.split()[-1]) != sim
    kernel.ok("world.drive(0.2)\nworld.wait_for_odom(lambda r: r.linear_mps > 0.15, 10)")


def test_restart_after_dead_simulation_serves_one_view(start_kernel) -> None:
    """The view lives in the simulation's process: it dies with it, one serves it after."""
    kernel = start_kernel()
    old_port, sim = _started(kernel)
    os.kill(sim, signal.SIGKILL)
    assert not wait_gone([sim], 5.0)
    with pytest.raises(OSError):  # nothing else still serves the dead world's view
        urllib.request.urlopen(f"http://127.0.0.1:{old_port}/static/", timeout=2)
    port, new_sim = _started(kernel)
    tree = process_tree(kernel.pid)
    serving = [p for p in tree if "--serve-view" in describe([p])]
    assert serving == [new_sim], describe(tree)
    assert not [p for p in tree if "viz.server" in describe([p])], describe(tree)
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/static/", timeout=5) as page:
        assert b"viewer.connect(base" in page.read()
