"""The live 3D view costs nothing unwatched (issue 23): LiveView sends a frame's poses only
while a browser is connected to the meshcat server and only when the robot moved, all of a
frame's poses in one websocket message; a browser that connects late gets the latest poses; a
page nobody can see (its notebook's tab in the background) gets none and is no watcher."""

from __future__ import annotations

import asyncio
import struct
import subprocess
import sys
import threading
import time
from collections.abc import Iterator

import mujoco
import pytest
import umsgpack
from suite_env import independent_env

from course_lib.core.waiting import wait_until
from course_lib.sim.view.live import LiveView
from course_lib.sim.world.model import build_model
from course_lib.viz.server import WATCHERS_COMMAND, serve_in_thread

pytestmark = [
    # meshcat's Visualizer(window=...) is given our window; its own socket is never opened
    pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning"),
]

PROBE_S = 0.1
QUIET_S = 0.3  # no message for this long: the server sent what it had
BASE = "/meshcat/mujoco/base_link"


class Browser:
    """A websocket client on the view (a browser tab's place): the messages it received."""

    def __init__(self, port: int) -> None:
        self.messages: list[bytes] = []
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, daemon=True)
        self.thread.start()
        self.connection = asyncio.run_coroutine_threadsafe(self._open(port), self.loop).result(10)

    async def _open(self, port: int):  # type: ignore[no-untyped-def]
        import tornado.websocket

        connection = await tornado.websocket.websocket_connect(f"ws://127.0.0.1:{port}/")
        self.reader = self.loop.create_task(self._read(connection))
        return connection

    async def _read(self, connection) -> None:  # type: ignore[no-untyped-def]
        while (message := await connection.read_message()) is not None:
            self.messages.append(message)

    def poses(self) -> list[dict]:
        """Return the pose messages received (one per frame)."""
        return [
            m
            for m in (umsgpack.unpackb(raw) for raw in list(self.messages))
            if m.get("type") == "set_transforms"
        ]

    def say(self, text: str) -> None:
        """Send what the viewer page sends when nobody can see it (`hidden`) or again (`shown`)."""
        self.loop.call_soon_threadsafe(self.connection.write_message, text)

    def settled(self) -> int:
        """Wait until no message came for QUIET_S (at most 10 s); return how many came."""
        count, since = len(self.messages), time.monotonic()
        deadline = since + 10.0
        while time.monotonic() < deadline and time.monotonic() - since < QUIET_S:
            time.sleep(0.02)
            if len(self.messages) != count:
                count, since = len(self.messages), time.monotonic()
        return count

    def poses_after(self, count: int) -> list[dict]:
        """Wait until at least `count` pose messages came (at most 10 s), then until no more
        come; return them all (a busy machine delays them, it does not lose them)."""
        wait_until(lambda: len(self.poses()) >= count, 10.0)
        self.settled()
        return self.poses()

    def close(self) -> None:
        """Close the websocket, wait until the reader saw it end (its socket closed), stop."""
        self.loop.call_soon_threadsafe(self.connection.close)
        wait_until(lambda: self.reader.done(), 5.0)
        self.loop.call_soon_threadsafe(self.loop.stop)
        self.thread.join(5)


def _robot() -> tuple[mujoco.MjModel, mujoco.MjData]:
    model = build_model()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


@pytest.fixture(params=["server process", "server thread"])
def view(request) -> Iterator[tuple[LiveView, mujoco.MjModel, mujoco.MjData, int]]:  # type: ignore[no-untyped-def]
    """A meshcat server and a LiveView drawing the robot on it: the server a child process
    (poses over its command socket) or a thread of this process, as in the simulation (poses
    handed over directly)."""
    if request.param == "server thread":
        yield from _view_on_a_thread()
        return
    server = subprocess.Popen(
        [sys.executable, "-m", "course_lib.viz.server"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        env=independent_env(),
    )
    try:
        assert server.stdout is not None
        zmq_url = server.stdout.readline().strip().split("=", 1)[1]
        web_url = server.stdout.readline().strip().split("=", 1)[1]
        port = int(web_url.rsplit(":", 1)[1].split("/")[0])
        model, data = _robot()
        live = LiveView(zmq_url, model, data, probe_period_s=PROBE_S)
        try:
            yield live, model, data, port
        finally:
            live.close()
    finally:
        server.terminate()
        server.wait(timeout=10)
        if server.stdout is not None:
            server.stdout.close()


def _view_on_a_thread() -> Iterator[tuple[LiveView, mujoco.MjModel, mujoco.MjData, int]]:
    server = serve_in_thread()
    try:
        model, data = _robot()
        live = LiveView(server.zmq_url, model, data, probe_period_s=PROBE_S, local=server)
        try:
            yield live, model, data, int(server.web_url.rsplit(":", 1)[1].split("/")[0])
        finally:
            live.close()
    finally:
        server.stop()


def _server_says_watchers(live: LiveView, count: int) -> None:
    """Wait until the server counts `count` watchers (a page's `hidden` or `shown` was read)."""
    assert wait_until(lambda: int(live.window.request(WATCHERS_COMMAND)) == count, 10.0)


def _tick(live: LiveView, model, data, *, moving: bool, ticks: int = 25) -> None:  # type: ignore[no-untyped-def]
    """Call update() at 50 Hz for `ticks` frames, moving the robot 1 cm a frame if `moving`."""
    for _ in range(ticks):
        if moving:
            data.qpos[0] += 0.01
            mujoco.mj_forward(model, data)
        live.update(data)
        if live.local is not None:  # one frame per tick: a busy machine's frames would merge
            wait_until(lambda: not live.local.sending, 5.0)
        time.sleep(0.02)


def test_nothing_is_sent_while_no_browser_watches(view) -> None:  # type: ignore[no-untyped-def]
    live, model, data, port = view
    _tick(live, model, data, moving=True, ticks=50)
    assert live.updates == 0, f"{live.updates} frames sent to a view nobody watches"
    browser = Browser(port)  # connects late: gets the scene and the latest poses
    try:
        _tick(live, model, data, moving=False, ticks=25)  # the probe finds the browser
        assert live.watchers == 1
        poses = browser.poses_after(1)
        assert poses, "a browser that connected late never got the robot's pose"
        matrices = poses[-1]["matrices"].data  # Float32Array: 16 floats per path, by column
        at = poses[-1]["paths"].index(BASE)
        x = struct.unpack_from("<f", matrices, (16 * at + 12) * 4)[0]
        assert abs(x - data.xpos[model.body("base_link").id][0]) < 1e-3
    finally:
        browser.close()


def test_a_watched_view_gets_one_message_per_moved_frame(view) -> None:  # type: ignore[no-untyped-def]
    live, model, data, port = view
    browser = Browser(port)
    try:
        _tick(live, model, data, moving=False, ticks=25)  # found; the first frame is sent
        sent = live.updates
        before = len(browser.poses_after(1))
        _tick(live, model, data, moving=False, ticks=25)
        browser.settled()
        assert live.updates == sent and len(browser.poses()) == before, "a still robot was sent"
        received = len(browser.messages)
        _tick(live, model, data, moving=True, ticks=20)
        browser.poses_after(before + 20)
        frames = [umsgpack.unpackb(m) for m in browser.messages[received:]]
        assert live.updates - sent == 20 and len(frames) == 20, (live.updates - sent, len(frames))
        assert all(f["type"] == "set_transforms" for f in frames)  # one message per frame
        assert all(BASE in f["paths"] and len(f["paths"]) > 3 for f in frames)
    finally:
        browser.close()
    _tick(live, model, data, moving=True, ticks=25)  # the browser left: the view stops
    assert live.watchers == 0


def test_a_hidden_page_gets_no_poses_and_is_no_watcher(view) -> None:  # type: ignore[no-untyped-def]
    """Poses piled up for a page in a background tab froze JupyterLab for 20 s when the tab
    came back (the robot driving for 30 s meanwhile): a hidden page gets none."""
    live, model, data, port = view
    seen, hidden = Browser(port), Browser(port)
    try:
        _tick(live, model, data, moving=True, ticks=10)
        assert live.watchers == 2
        hidden.say("hidden")
        _server_says_watchers(live, 1)
        seen.settled()
        before_seen, before_hidden = len(seen.poses()), len(hidden.poses())
        _tick(live, model, data, moving=True, ticks=20)
        assert len(seen.poses_after(before_seen + 20)) - before_seen == 20
        hidden.settled()
        assert len(hidden.poses()) == before_hidden, "a hidden page was sent poses"
        assert live.watchers == 1
        seen.say("hidden")
        _server_says_watchers(live, 0)
        _tick(live, model, data, moving=True, ticks=20)
        assert live.watchers == 0  # nobody sees the view: the simulation sends nothing
        sent = live.updates
        _tick(live, model, data, moving=True, ticks=20)
        assert live.updates == sent
        hidden.say("shown")  # its tab in front again: the latest poses at once, then each move
        assert len(hidden.poses_after(before_hidden + 1)) == before_hidden + 1
        _tick(live, model, data, moving=False, ticks=25)  # the probe finds it
        poses = hidden.poses_after(before_hidden + 1)
        at = poses[-1]["paths"].index(BASE)
        x = struct.unpack_from("<f", poses[-1]["matrices"].data, (16 * at + 12) * 4)[0]
        assert abs(x - data.xpos[model.body("base_link").id][0]) < 1e-3, "the view is stale"
    finally:
        seen.close()
        hidden.close()


def test_the_simulation_never_waits_for_its_own_view_server() -> None:
    """The physics loop hands a frame to a server thread of its own process and goes on: a
    server busy for seconds (its thread stalled) costs the loop nothing, and once it runs
    again the browser gets the latest poses once, not a burst of the frames it missed."""
    views = _view_on_a_thread()
    live, model, data, port = next(views)
    browser = Browser(port)
    try:
        _tick(live, model, data, moving=True, ticks=10)
        assert live.watchers == 1
        before = len(browser.poses_after(1))
        assert live.local is not None
        stalled = threading.Event()
        live.local.bridge.ioloop.add_callback(stalled.wait, 3.0)
        started = time.monotonic()
        for _ in range(5):  # five frames while the server's thread is stalled
            data.qpos[0] += 0.01
            mujoco.mj_forward(model, data)
            assert live.update(data)
        assert time.monotonic() - started < 0.5, "the loop waited for a stalled view server"
        stalled.set()
        poses = browser.poses_after(before + 1)
        assert len(poses) == before + 1, f"{len(poses) - before} frames came after the stall"
        matrices = poses[-1]["matrices"].data  # Float32Array: 16 floats per path, by column
        x = struct.unpack_from("<f", matrices, (16 * poses[-1]["paths"].index(BASE) + 12) * 4)[0]
        assert abs(x - data.xpos[model.body("base_link").id][0]) < 1e-3  # the latest pose
    finally:
        browser.close()
        views.close()
