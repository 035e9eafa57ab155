"""A deleted account's runtime folder is not handed to the next account with its uid (real hub,
real accounts).

An account of the host used the course (its parameter journal, with what it set, sits in its
runtime folder, named by uid), then was deleted; the administrator made a learner of the class
with the same uid before the hub started. Another uid's folder was left with no account at all.
"""

from __future__ import annotations

import json
import os
import pwd
import secrets
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from class_hub import ClassHub, remove_account, uid_of
from hub_accounts import as_account, sign_in

pytestmark = [pytest.mark.slow, pytest.mark.learners_env]

OLD, NEW, ADMIN = "r2pu-old", "r2pu-new", "r2pu-adm"
DEBIAN_PYTHON = "/usr/bin/python3"  # every account may run it (the course's may be root's)

# Run as an account: write a journal line (the secret, from stdin) in its runtime folder, as
# course_lib/core/param_journal.py does (0700 folder in the temp folder Python names, 0600 file).
_WRITE_JOURNAL = r"""
import os, sys, tempfile
folder = os.path.join(tempfile.gettempdir(), f"ros2-course-{os.getuid()}")
os.makedirs(folder, 0o700, exist_ok=True)
fd = os.open(os.path.join(folder, "param-journal-0.jsonl"), os.O_WRONLY | os.O_CREAT, 0o600)
os.write(fd, ('{"t": "set", "name": "max_speed", "value": "%s"}\n' % sys.stdin.read()).encode())
os.close(fd)
print(folder)
"""

# Run as an account: every file of its runtime folders it can read; which hold the secret.
_READ_JOURNALS = r"""
import json, os, sys, tempfile
secret, uid, found = sys.stdin.read().strip(), os.getuid(), []
for top in {tempfile.gettempdir(), "/tmp"}:
    for folder, _, files in os.walk(os.path.join(top, f"ros2-course-{uid}")):
        for name in files:
            try:
                with open(os.path.join(folder, name), encoding="utf-8", errors="replace") as f:
                    if secret in f.read():
                        found.append(os.path.join(folder, name))
            except OSError:
                pass
print(json.dumps(found))
"""


def _free_uid() -> int:
    """Return a uid with no account and no runtime folder in the temp folder."""
    for uid in range(59999, 50000, -1):
        folder = Path(tempfile.gettempdir()) / f"ros2-course-{uid}"
        if not _has_account(uid) and not os.path.lexists(folder):
            return uid
    raise AssertionError("no free uid between 50000 and 59999")


def _has_account(uid: int) -> bool:
    try:
        pwd.getpwuid(uid)
    except KeyError:
        return False
    return True


def _lay_out(secret: str, laid: dict[str, Path]) -> None:
    """Make OLD, let it write its journal, delete it, make NEW with its uid; leave a folder of
    a uid with no account, and one of a uid that owns none of it."""
    remove_account(OLD)
    account = ["--create-home", "--user-group", "--shell", "/bin/bash"]
    subprocess.run(["useradd", *account, OLD], check=True, capture_output=True)
    wrote = as_account(OLD, [DEBIAN_PYTHON, "-c", _WRITE_JOURNAL], {}, stdin=secret)
    assert wrote.returncode == 0, wrote.stderr
    laid["journal_folder"] = Path(wrote.stdout.strip())
    uid = uid_of(OLD)
    remove_account(OLD)  # userdel --remove: its home goes, its runtime folder stays
    subprocess.run(["useradd", *account, "--uid", str(uid), NEW], check=True, capture_output=True)
    orphan = _free_uid()
    laid["orphan"] = Path(tempfile.gettempdir()) / f"ros2-course-{orphan}"
    laid["orphan"].mkdir(0o700)
    (laid["orphan"] / "param-journal-3.jsonl").write_text(f'"{secret}"\n', encoding="utf-8")
    shutil.chown(laid["orphan"] / "param-journal-3.jsonl", orphan, orphan)
    shutil.chown(laid["orphan"], orphan, orphan)
    # named for a uid with no account, but root's: not a runtime folder that uid left
    laid["not_its"] = Path(tempfile.gettempdir()) / f"ros2-course-{_free_uid()}"
    laid["not_its"].mkdir(0o700)


@pytest.fixture(scope="module")
def secret() -> str:
    return secrets.token_hex(16)


@pytest.fixture(scope="module")
def laid() -> dict[str, Path]:
    """What the layout made before the hub started."""
    return {}


@pytest.fixture(scope="module")
def hub(
    tmp_path_factory: pytest.TempPathFactory, secret: str, laid: dict[str, Path]
) -> Iterator[ClassHub]:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    folder = tmp_path_factory.mktemp("runtime-leftovers-hub")
    config = folder / "hub.yaml"
    config.touch(0o600)  # it holds the demo's password: the hub refuses it open to others
    started = None
    try:  # the layout is removed even if the hub does not start
        started = ClassHub(
            (NEW,), (ADMIN,), folder, config=config,
            settings="authenticator: shared-password\nshared_password: r2pu-demo-password\n",
            before_start=lambda: _lay_out(secret, laid),
        )  # fmt: skip
        started.passwords = {NEW: "r2pu-demo-password"}
        yield started
    finally:
        if started is not None:
            (folder / "hub.log").write_text(started.log(), encoding="utf-8")
            started.stop()  # removes the class's accounts
        for name in (OLD, NEW):
            remove_account(name)
        for key in ("journal_folder", "orphan", "not_its"):
            if key in laid:
                shutil.rmtree(laid[key], ignore_errors=True)


def test_a_new_account_with_a_deleted_ones_uid_cannot_read_its_journal(
    hub: ClassHub, secret: str, laid: dict[str, Path]
) -> None:
    """The course checks only that its runtime folder is the uid's: the new learner's lab took
    the deleted account's folder as its own and read its 52 KB parameter journal."""
    sign_in(hub, NEW)  # their server runs: its lab has made its runtime folder again
    read = as_account(NEW, [DEBIAN_PYTHON, "-c", _READ_JOURNALS], {}, stdin=secret)
    assert read.returncode == 0, read.stderr
    assert json.loads(read.stdout) == [], f"{NEW} read the deleted account's journal"
    removed = f"Removed {laid['journal_folder']} before {NEW}'s server started"
    assert removed in hub.log(), hub.log()[-4000:]


def test_a_runtime_folder_of_a_uid_with_no_account_is_gone_after_the_hubs_start(
    hub: ClassHub, laid: dict[str, Path]
) -> None:
    """Nothing removed it: the next account given that uid (by the hub, say) inherited it."""
    assert not os.path.lexists(laid["orphan"])
    # which hub's log says so: another hub test starting beside this one removes it as well
    # (what its line says is tests/unit/hub/test_runtime_leftovers.py's)
    assert laid["not_its"].is_dir(), "a folder that uid does not own was removed"
