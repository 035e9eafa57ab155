"""The hub's locks: a hub that finds one held says who holds it, waits a bounded time, then
stops with a message naming them (before: it waited in silence for as long as they liked)."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from course_lib.hub.guard.locks import LOCKS_FOLDER, LockWaitError, hub_lock, lock_holders

_HOLD = """
import sys, time
from pathlib import Path
from course_lib.hub.guard.locks import hub_lock
with hub_lock(Path(sys.argv[1]), "build", "a build"):
    print("held", flush=True)
    time.sleep(60)
"""


def _another_hub(environment: Path) -> subprocess.Popen[str]:
    """Start a process that holds `environment`'s build lock, as a second hub's build does."""
    holder = subprocess.Popen(
        [sys.executable, "-c", _HOLD, str(environment)], stdout=subprocess.PIPE, text=True
    )
    assert holder.stdout is not None and holder.stdout.readline() == "held\n"
    return holder


def test_a_held_lock_is_named_then_given_up_after_its_timeout(tmp_path: Path) -> None:
    holder = _another_hub(tmp_path)
    said: list[str] = []
    try:
        assert lock_holders(tmp_path / LOCKS_FOLDER / "build") == [holder.pid]
        started = time.monotonic()
        held_by = rf"Waited 2 s for a build, held by pid {holder.pid}"
        with (
            pytest.raises(LockWaitError, match=held_by),
            hub_lock(tmp_path, "build", "a build", say=said.append, timeout=2.0),
        ):
            pytest.fail("the lock was taken while another process held it")
        assert 2.0 <= time.monotonic() - started < 10.0
    finally:
        holder.kill()
        holder.communicate()
    assert len(said) == 1 and f"pid {holder.pid}" in said[0], said
    with hub_lock(tmp_path, "build", "a build", say=said.append, timeout=2.0):
        pass  # its holder has gone: taken at once, nothing said
    assert len(said) == 1


def test_the_locks_folder_is_the_hubs_alone(tmp_path: Path) -> None:
    (tmp_path / ".build.lock").write_text("")  # an older hub's, open to every account
    (tmp_path / LOCKS_FOLDER).mkdir(mode=0o755)
    with hub_lock(tmp_path, "build", "a build"):
        folder = (tmp_path / LOCKS_FOLDER).stat()
        lock = (tmp_path / LOCKS_FOLDER / "build").stat()
    assert stat.S_IMODE(folder.st_mode) == 0o700 and folder.st_uid == os.geteuid()
    assert stat.S_IMODE(lock.st_mode) & 0o077 == 0
    assert not (tmp_path / ".build.lock").exists()


def test_a_link_in_place_of_the_locks_folder_is_refused(tmp_path: Path) -> None:
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (tmp_path / "env").mkdir()
    (tmp_path / "env" / LOCKS_FOLDER).symlink_to(elsewhere)
    with (
        pytest.raises(Exception, match="is not a folder of the hub's account"),
        hub_lock(tmp_path / "env", "build", "a build"),
    ):
        pass
    assert list(elsewhere.iterdir()) == []
