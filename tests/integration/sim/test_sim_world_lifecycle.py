"""start_world's failure modes and clean-up: config errors, the viewer server's lifetime."""

from __future__ import annotations

import urllib.request
from pathlib import Path

import pytest

from course_lib.core.errors import ConfigError
from course_lib.core.host.procfs import pid_alive
from course_lib.notebook import start_world
from course_lib.session.session import Session

pytestmark = [pytest.mark.ros, pytest.mark.sim]


def _serves_viewer(port: int) -> bool:
    """Return True if our meshcat viewer page answers on `port` (the port alone may be reused)."""
    try:
        page = urllib.request.urlopen(f"http://127.0.0.1:{port}/static/", timeout=2).read()
    except OSError:
        return False
    return b"viewer.connect(base" in page


def test_bad_config_raises_before_anything_starts(tmp_path: Path, session: Session) -> None:
    bad = tmp_path / "simulation.yaml"
    bad.write_text("rates:\n  odom_hz: 50\n  scan_hz: often\n")
    with pytest.raises(ConfigError) as caught:
        start_world(session, show=False, config=bad)
    assert (caught.value.line, caught.value.key) == (3, "rates.scan_hz")
    assert caught.value.path.endswith("simulation.yaml")
    assert session.children == []


def test_viewer_server_is_gone_after_the_session_closes() -> None:
    own = Session()
    try:
        world = start_world(own, show=False)
        assert world.viewer is None
        world.stop()
        world = start_world(own, show=True)
        port = world.viewer.port
        assert _serves_viewer(port)
        command_socket = Path(world.viewer.zmq_url.removeprefix("ipc://"))
        assert command_socket.exists()
        processes = [world.process, world.viewer.process]
    finally:
        own.close()
    assert not any(p.alive for p in processes)
    assert not _serves_viewer(port)
    assert not command_socket.exists()  # the simulation removed its view's socket file


OWNER = """
import sys
from course_lib.session.session import Session
from course_lib.notebook import start_world
world = start_world(Session(), show=True)
print("PIDS", world.process.pid, world.viewer.process.pid, world.viewer.port, flush=True)
sys.stdin.read()
"""


def test_a_killed_kernel_leaves_no_world_behind() -> None:
    import signal
    import subprocess
    import sys
    import threading
    import time

    owner = subprocess.Popen(
        [sys.executable, "-c", OWNER], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    try:
        line = ""
        while not line.startswith("PIDS"):
            line = owner.stdout.readline()
            assert line, "the owner process ended early"
        sim_pid, viewer_pid, port = (int(v) for v in line.split()[1:])
        owner.send_signal(signal.SIGKILL)
        owner.wait(5)
        deadline = time.monotonic() + 2.0
        while time.monotonic() < deadline and (pid_alive(sim_pid) or pid_alive(viewer_pid)):
            threading.Event().wait(0.05)
        assert not pid_alive(sim_pid) and not pid_alive(viewer_pid)
        assert not _serves_viewer(port)
    finally:
        owner.kill()
        owner.wait(5)
        owner.stdout.close()
        owner.stdin.close()


def test_a_world_asked_to_stop_ends_at_once(session: Session) -> None:
    """The world's `/cmd_vel` thread waits up to 30 s for a message; stopping the world shuts
    its executor down, which must end that wait then (else close() gives up after 2 s)."""
    import time

    world = start_world(session, show=False)
    world.odom()
    time.sleep(1.5)  # the robot rests: the thread waits in its executor
    started = time.monotonic()
    world.stop()
    took = time.monotonic() - started
    assert not world.process.alive
    assert world.process.returncode == 0
    assert took < 1.5, f"stop() took {took:.2f} s"
