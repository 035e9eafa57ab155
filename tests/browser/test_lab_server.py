"""A test's lab is handed over only once its JupyterLab answers.

Jupyter Server prints its address before it listens; on two busy cores the gap was long enough
for test_lab_daemon.py's first request to be refused. Here the gap is made 2 s long
(slow_to_listen.py), and the first request, sent at once and never retried, must be answered.
"""

from __future__ import annotations

import json
import os
import shutil
import urllib.request
from pathlib import Path

import pytest
from lab_server import ARTIFACTS, LabServer

from course_lib.tools.testing import independent_env

pytestmark = [pytest.mark.ros, pytest.mark.slow]

HERE = Path(__file__).resolve().parent
EXTENSION = "--ServerApp.jpserver_extensions=slow_to_listen=True"


def test_a_lab_slow_to_listen_answers_its_first_request() -> None:
    folder = ARTIFACTS / "lab-slow-to-listen"
    shutil.rmtree(folder, ignore_errors=True)
    path = os.pathsep.join(p for p in (str(HERE), os.environ.get("PYTHONPATH", "")) if p)
    lab = LabServer([], folder, env=independent_env(PYTHONPATH=path), extra=[EXTENSION])
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
