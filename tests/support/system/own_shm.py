"""Run a Python program with a /dev/shm of its own (root and `unshare`, as in the CI).

Fast DDS keeps its shared-memory ports and segments in /dev/shm, host-wide: a test that holds
their locks or counts their files does it in a tmpfs of its own, where other tests' processes
neither see nor disturb it.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import pytest

from course_lib.core.paths import REPO_ROOT
from course_lib.processes.domain import lease_domain
from course_lib.session.session import session_env

__all__ = ["domain_env", "run_in_own_shm"]


@contextmanager
def domain_env() -> Iterator[dict[str, str]]:
    """Yield the environment of a session on a leased domain (the course importable)."""
    lease = lease_domain({})
    try:
        yield {**session_env(lease.domain_id), "PYTHONPATH": str(REPO_ROOT)}
    finally:
        lease.release()


def run_in_own_shm(program: str, *args: str, env: dict[str, str], timeout: float) -> Any:
    """Run `python -c program args...` in a /dev/shm of its own; return the JSON of the last
    line it printed (skip the test without root or `unshare`)."""
    unshare = shutil.which("unshare")
    if unshare is None or os.geteuid() != 0:
        pytest.skip("needs root and `unshare` for a /dev/shm of its own (the CI runs as root)")
    script = f'mount -t tmpfs tmpfs /dev/shm && exec {sys.executable} -c "$0" "$@"'
    done = subprocess.run(
        [unshare, "--mount", "sh", "-c", script, program, *args],
        env=env, capture_output=True, text=True, timeout=timeout, check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.splitlines()[-1])
