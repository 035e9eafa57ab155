"""Two hubs started at once on a fresh host install the proxy one after the other: a second
`npm ci` in the same folder deleted the first one's node_modules under it ("npm could not
install configurable-http-proxy", a rerun in the suite when two hub tests started together)."""

from __future__ import annotations

import shutil
import threading
import time
from pathlib import Path

import pytest

from course_lib.hub.guard.locks import hub_lock
from course_lib.hub.provision.proxy import install_proxy, proxy_command

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(shutil.which("npm") is None, reason="npm installs the hub's proxy"),
]


def test_an_install_waits_while_another_one_is_at_work(tmp_path: Path) -> None:
    done: list[Path] = []
    with hub_lock(tmp_path, "proxy", "an install"):  # another hub's install under way
        thread = threading.Thread(target=lambda: done.append(install_proxy(tmp_path)))
        thread.start()
        time.sleep(1.0)
        assert not (tmp_path / "proxy").exists(), "an install began while another one ran"
    thread.join(120.0)
    assert done == [proxy_command(tmp_path)] and done[0].exists()
    started = time.monotonic()
    assert install_proxy(tmp_path) == done[0]  # installed: the next hub waits for nothing
    assert time.monotonic() - started < 1.0
