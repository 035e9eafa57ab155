"""Run a test's scenario in a PID namespace of its own (its pids, its `make stop`)."""

from __future__ import annotations

import os
import shutil
import subprocess

import pytest

__all__ = ["namespace_prefix"]


def namespace_prefix(why: str) -> list[str]:
    """Return the command prefix that runs a process in a new PID namespace, or skip saying
    what `unshare` would have given the test (`why`)."""
    unshare = shutil.which("unshare")
    if unshare is None:
        pytest.skip(f"`unshare` (util-linux) is missing: it {why}")
    prefix = [unshare, "--pid", "--fork", "--mount-proc", "--kill-child"]
    if os.geteuid() != 0:
        prefix[1:1] = ["--user", "--map-root-user"]
    probe = subprocess.run([*prefix, "true"], capture_output=True, check=False)
    if probe.returncode != 0:
        pytest.skip(f"no PID namespace here ({probe.stderr.decode().strip()}): run as root, as CI")
    return prefix
