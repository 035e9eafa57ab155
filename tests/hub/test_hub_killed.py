"""A hub killed outright takes its proxy with it (tied); the progress service is the launcher's."""

from __future__ import annotations

import contextlib
import signal
import time

import psutil
import pytest
from progress_hub import ClassHub


def test_a_killed_hub_leaves_no_proxy_or_service(
    tmp_path_factory: pytest.TempPathFactory, proxy: str
) -> None:
    hub = ClassHub(tmp_path_factory.mktemp("killed-hub"), proxy)
    hub.start()
    assert hub.process is not None
    children = psutil.Process(hub.process.pid).children(recursive=True)
    try:
        commands = [" ".join(child.cmdline()) for child in children]
        assert any("configurable-http-proxy" in c for c in commands), commands
        # the progress service is the launcher's child, not the hub's (the launcher hands it
        # its socket): test_progress_process.py kills a launcher
        assert not any("course_lib.hub.progress" in c for c in commands), commands
        hub.process.send_signal(signal.SIGKILL)
        hub.process.wait()
        deadline = time.monotonic() + 10.0
        while left := [c for c in children if c.is_running() and c.status() != "zombie"]:
            assert time.monotonic() < deadline, [c.cmdline() for c in left]
            time.sleep(0.1)
    finally:
        for child in children:  # what outlived the hub, when the check failed: the test's own
            with contextlib.suppress(psutil.Error):
                child.kill()
        hub.close()
