"""No account can stall `make hub` by holding one of its locks (real accounts, the real build).

The hub builds the learners' environment and installs its proxy under a lock, so that two
hubs never do it together. The lock files were in the environment, readable by every account:
an account of the host that is in no class opened them read-only, held an exclusive `flock`,
and `make hub` waited in silence until it let go (45 s in the issue's try, as long as it
liked). Here that account holds every lock file of the hub it can open while a hub builds.
"""

from __future__ import annotations

import json
import os
import pwd
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from class_hub import hub_environment, remove_account

from course_lib.core.paths import REPO_ROOT
from course_lib.hub.guard.locks import LOCKS_FOLDER

pytestmark = [pytest.mark.slow, pytest.mark.learners_env]

OUTSIDER = "r2pl-out"
DEBIAN_PYTHON = "/usr/bin/python3"  # every account may run it (the course's may be root's)
BUILD_WAIT_S = 300.0  # the build of a built environment: make's stamps, seconds

# Run as the outsider: hold an exclusive flock on every lock file it can open, say which.
_HOLD = r"""
import fcntl, json, os, sys, time
held, refused = [], {}
for path in sys.argv[1:]:
    try:
        fd = os.open(path, os.O_RDONLY)
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        held.append(path)
    except OSError as err:
        refused[path] = err.strerror
print(json.dumps({"held": held, "refused": refused}), flush=True)
time.sleep(3600)
"""

_BUILD = (
    "import sys; from pathlib import Path\n"
    "from course_lib.hub.provision.environment import build_environment\n"
    "from course_lib.hub.provision.proxy import install_proxy\n"
    "build_environment(Path(sys.argv[1]), Path(sys.argv[2]))\n"
    "install_proxy(Path(sys.argv[1]))\n"
    "print('built', flush=True)\n"
)


@pytest.fixture
def outsider() -> Iterator[str]:
    if os.geteuid() != 0:
        pytest.skip("the attack needs an account of its own: run as root (CI does)")
    remove_account(OUTSIDER)
    argv = ["useradd", "--create-home", "--user-group", "--shell", "/bin/bash", OUTSIDER]
    subprocess.run(argv, check=True, capture_output=True)
    try:
        yield OUTSIDER
    finally:
        remove_account(OUTSIDER)


def _as(name: str, argv: list[str]) -> subprocess.Popen[str]:
    account = pwd.getpwnam(name)

    def become() -> None:
        os.setgroups([])
        os.setgid(account.pw_gid)
        os.setuid(account.pw_uid)

    return subprocess.Popen(
        argv, preexec_fn=become, cwd="/", stdout=subprocess.PIPE, text=True,
        env={"HOME": account.pw_dir, "PATH": os.defpath},
    )  # fmt: skip


def _lock_files(environment: Path) -> list[str]:
    """Every file a lock of the hub is (or was) in: the old places and the new folder."""
    names = [".build.lock", ".proxy.lock"]
    names += [f"{LOCKS_FOLDER}/{name}" for name in ("build", "proxy")]
    return [str(environment / name) for name in names]


def test_an_account_holding_the_hubs_locks_does_not_stall_its_build(outsider: str) -> None:
    environment = hub_environment()
    build = [sys.executable, "-c", _BUILD, str(environment), "/usr/bin/python3.11"]
    first = subprocess.run(build, cwd=REPO_ROOT, capture_output=True, text=True, timeout=1200)
    assert first.returncode == 0, first.stderr[-3000:]  # the environment is there
    holder = _as(outsider, [DEBIAN_PYTHON, "-c", _HOLD, *_lock_files(environment)])
    try:
        assert holder.stdout is not None
        report = json.loads(holder.stdout.readline())
        try:
            again = subprocess.run(
                build, cwd=REPO_ROOT, capture_output=True, text=True, timeout=BUILD_WAIT_S
            )
        except subprocess.TimeoutExpired:
            pytest.fail(
                f"the hub's build waited {BUILD_WAIT_S:.0f} s for {outsider}, who held "
                f"{report['held']}"
            )
        assert again.returncode == 0 and "built" in again.stdout, again.stderr[-3000:]
        assert not any(LOCKS_FOLDER in path for path in report["held"]), report
        for name in ("build", "proxy"):
            refused = report["refused"][str(environment / LOCKS_FOLDER / name)]
            assert refused == "Permission denied", report
    finally:
        holder.kill()
        holder.communicate()
