"""A test's lab is handed over only once its JupyterLab answers.

Jupyter Server prints its address before it listens; on two busy cores the gap was long enough
for test_lab_daemon.py's first request to be refused. Here the gap is made 2 s long
(slow_to_listen.py), and the first request, sent at once and never retried, must be answered.
"""

from __future__ import annotations

import json
import os
import shutil
import time
import urllib.request
from pathlib import Path

import pytest
from lab_server import ARTIFACTS, LabServer
from suite_env import independent_env

pytestmark = [pytest.mark.ros, pytest.mark.slow]

HERE = Path(__file__).resolve().parent
EXTENSION = "--ServerApp.jpserver_extensions=slow_to_listen=True"
SPAWN_LOG = "--ServerApp.jpserver_extensions=spawn_log=True"
LESSON = "01_setup_check.ipynb"


def test_a_lab_slow_to_listen_answers_its_first_request() -> None:
    folder = ARTIFACTS / "lab-slow-to-listen"
    shutil.rmtree(folder, ignore_errors=True)
    lab = LabServer([], folder, env=_with_extensions_here(), extra=[EXTENSION])
    try:
        assert "slow_to_listen | extension was successfully loaded" in lab.process.text()
        request = urllib.request.Request(
            f"{lab.base_url}/api/terminals",
            method="POST",
            headers={"Authorization": f"token {lab.token}"},
        )
        opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))
        with opener.open(request, timeout=30) as reply:  # at once, and only once
            assert json.loads(reply.read())["name"]
    finally:
        lab.stop()


@pytest.mark.browser
def test_a_page_load_starts_no_node_program(browser) -> None:  # type: ignore[no-untyped-def]
    """A hub host has Node.js (for its proxy): JupyterLab then ran `npm prefix -g` (looking
    for language servers) and `node` twice (a build check) on each lab's start and page load,
    about 2.4 CPU-seconds on a busy 2-core host, for what no learner uses."""
    from spawn_log import SPAWN_LOG_ENV

    folder = ARTIFACTS / "lab-spawn-log"
    shutil.rmtree(folder, ignore_errors=True)
    log = folder / "spawned.jsonl"
    env = _with_extensions_here(**{SPAWN_LOG_ENV: str(log)})
    lab = LabServer([LESSON], folder, env=env, extra=[SPAWN_LOG])
    page = browser.new_page(viewport={"width": 1280, "height": 1000})
    try:
        page.goto(lab.lab_url(LESSON))
        page.locator(".jp-Notebook").first.wait_for(timeout=90_000)
        # the lesson starts its kernel as it opens (the course's settings): the log works
        deadline = time.monotonic() + 60
        while "kernel_launcher" not in _read(log) and time.monotonic() < deadline:
            time.sleep(0.2)
        page.wait_for_timeout(3000)  # what the page asks for as it starts has been asked
        spawned = [json.loads(line) for line in _read(log).splitlines()]
        assert any("kernel_launcher" in " ".join(argv) for argv in spawned), (spawned, lab.text())
        node = [argv for argv in spawned if Path(argv[0]).name in {"node", "npm", "yarn"}]
        assert not node, f"the lab started Node.js programs: {node}"
    finally:
        page.close()
        lab.stop()


def _with_extensions_here(**extra: str) -> dict[str, str]:
    """Return a lab's environment in which this folder's server extensions can be loaded."""
    path = os.pathsep.join(p for p in (str(HERE), os.environ.get("PYTHONPATH", "")) if p)
    return independent_env(PYTHONPATH=path, **extra)


def _read(path: Path) -> str:
    return path.read_text(encoding="utf-8") if path.exists() else ""
