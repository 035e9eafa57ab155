"""A notebook whose kernel connection is left "Unknown" after a restart connects again by
itself (the course's lab extension), so cells run again without the learner's help.

Found by `make chaos` (issue 62): a kernel killed while Run All ran came back on the server
(idle), but now and then the page's connection stayed "Unknown" and every cell waited behind it
for ever (the server, idle, answered nothing on that socket; JupyterLab waits on an open socket for
ever). Here the socket breaks on purpose: the page's kernel websocket is routed through the
test, which passes nothing from the server on from a restart on; then the first heal's socket
breaks too (a chaos walk saw "Unknown" for 300 s: the extension healed once and never again).
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest

pytestmark = [pytest.mark.browser, pytest.mark.ros, pytest.mark.slow]

LESSONS = ["02_key_points.ipynb"]
# the extension reconnects after 10 s of "unknown" and restarts the kernel (seen taking 20 s
# more on 2 busy cores in a whole suite run); a heal that did not take is tried again a minute on
HEAL_AGAIN_S = 60.0
HEALED_WITHIN_S = 60.0 + HEAL_AGAIN_S
_STATE = """() => {
  const context = window.jupyterapp.shell.currentWidget.sessionContext;
  const kernel = context.session?.kernel;
  return [kernel?.id, kernel?.status, kernel?.connectionStatus, !!context.__ros2CourseHeals];
}"""  # the extension reconnects after 10 s of "unknown"


def test_a_kernel_connection_stuck_unknown_connects_again(  # type: ignore[no-untyped-def]
    lab_page, artifacts: Path
) -> None:
    page = lab_page.page
    sockets: list[dict[str, object]] = []  # each kernel websocket: whether its bridge broke
    said: list[str] = []
    page.on("console", lambda message: said.append(message.text))

    break_next = {"armed": 0}  # how many sockets opened from now on pass nothing on

    def route(ws) -> None:  # type: ignore[no-untyped-def]
        state: dict[str, object] = {"broken": break_next["armed"] > 0, "dropped": 0}
        break_next["armed"] = max(0, break_next["armed"] - 1)
        sockets.append(state)
        server = ws.connect_to_server()
        ws.on_message(server.send)

        def from_server(message) -> None:  # type: ignore[no-untyped-def]
            if state["broken"]:  # the server's side of this socket passes nothing on
                state["dropped"] = int(state["dropped"]) + 1  # type: ignore[call-overload]
                return
            ws.send(message)

        server.on_message(from_server)

    page.route_web_socket(re.compile(r"/api/kernels/[^/]+/channels"), route)
    page.reload()  # the route applies to the websockets of pages loaded from now on
    page.locator(".jp-DirListing-item").first.wait_for()
    lab_page.open(LESSONS[0])
    assert sockets, "the kernel's websocket was not routed: nothing would be tested"

    opened = len(sockets)
    # the restart's socket passes nothing on, nor do the first heal's two (it connects again,
    # then restarts the kernel, which connects once more)
    break_next["armed"] = 3
    lab_page.restart_kernel()
    stuck_since = time.monotonic()
    page.wait_for_timeout(3000)
    assert "Unknown" in lab_page.kernel_status(), lab_page.kernel_status()

    while "Idle" not in lab_page.kernel_status():
        assert time.monotonic() - stuck_since < HEALED_WITHIN_S, (
            f"still {lab_page.kernel_status()!r} {HEALED_WITHIN_S:g} s after the connection broke:"
            f" {page.evaluate(_STATE)} {sockets} {[t for t in said if 'ros2' in t]}"
        )
        page.wait_for_timeout(500)
    assert len(sockets) >= opened + 4, "healed without a second heal's connection?"
    assert all(s["broken"] for s in sockets[opened : opened + 3]), sockets
    assert sockets[opened]["dropped"], sockets
    assert time.monotonic() - stuck_since > HEAL_AGAIN_S, "healed before the second try?"
    assert any("reconnecting" in text for text in said), said
    cell = lab_page.add_cell("print(6 * 7)")
    lab_page.screenshot(artifacts / "healed.png")
    assert "42" in cell.text, cell.text


def test_a_notebook_runs_again_after_its_server_was_killed(  # type: ignore[no-untyped-def]
    lab_page, artifacts: Path
) -> None:
    """The lab starts a killed server again; its notebooks' old kernels are gone with it. The
    page lets go of the old session (its status bar may still say "Disconnected") and the next
    cell run starts a new kernel: what the learner typed runs."""
    import signal

    import psutil

    said: list[str] = []
    lab_page.page.on("console", lambda message: said.append(message.text))
    lab_page.open(LESSONS[0])
    root = psutil.Process(lab_page.lab.process.pid)
    server = next(c for c in root.children() if "jupyter" in " ".join(c.cmdline()[:2]))
    server.send_signal(signal.SIGKILL)
    since = time.monotonic()
    lab_page.page.wait_for_timeout(3000)  # the page has noticed: its status no longer "Idle"
    while lab_page.page.evaluate(_STATE)[0] is not None:  # the old kernel: still its session's
        assert time.monotonic() - since < HEALED_WITHIN_S, (
            f"{lab_page.kernel_status()!r} {lab_page.page.evaluate(_STATE)}"
            f" {[t for t in said if 'ros2' in t]}"
        )
        lab_page.page.wait_for_timeout(500)
    lab_page.dismiss_dialogs()
    cell = lab_page.add_cell("print(6 * 7)")
    lab_page.screenshot(artifacts / "after-server-killed.png")
    assert "42" in cell.text, cell.text
