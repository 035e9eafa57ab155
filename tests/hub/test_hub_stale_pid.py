"""A hub killed outright leaves its proxy's pid file; by the next start that pid may be any
process's. `make hub` (root) must signal nobody but its own old proxy (real hub)."""

from __future__ import annotations

import os
import subprocess
from collections.abc import Iterator

import pytest
from class_hub import ClassHub

pytestmark = [pytest.mark.slow, pytest.mark.learners_env]


@pytest.fixture(scope="module")
def bystander() -> Iterator[subprocess.Popen[bytes]]:
    process = subprocess.Popen(["sleep", "600"])
    try:
        yield process
    finally:
        process.kill()
        process.wait()


def test_a_stale_proxy_pid_file_gets_nobody_signalled(
    tmp_path_factory: pytest.TempPathFactory, bystander: subprocess.Popen[bytes]
) -> None:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    folder = tmp_path_factory.mktemp("stale-pid-hub")
    (folder / "state").mkdir(mode=0o700)
    (folder / "state" / "proxy.pid").write_text(f"{bystander.pid}\n")
    hub = ClassHub(("r2pw-sam",), ("r2pw-sad",), folder)
    try:
        assert bystander.poll() is None, f"the hub signalled pid {bystander.pid}"
        assert "which is not the hub's proxy any more: it is left alone" in hub.log()
    finally:
        hub.stop()
