"""The learners' socket folders of a killed hub go at the next hub's start; a running hub's,
or one of another PID namespace, never do."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from course_lib.core.host.ports import free_port
from course_lib.core.host.procfs import pid_namespace
from course_lib.hub import launcher
from course_lib.hub.guard.wall import wall_problem
from course_lib.hub.launcher import WALL_OWNER, WALL_PREFIX, forget_stale_wall_folders
from course_lib.processes.orphans import owner_tag


def _dead_owner() -> str:
    """Return the owner tag of a process that has ended since."""
    sleeper = subprocess.Popen(["sleep", "30"])
    tag = owner_tag(sleeper.pid)
    sleeper.kill()
    sleeper.wait()
    return tag


def _folder(run: Path, port: int, owner: str | None) -> Path:
    folder = run / f"{WALL_PREFIX}{port}"
    (folder / "learner-a").mkdir(parents=True)
    (folder / "learner-a" / "server.sock").touch()  # what a killed server left
    if owner is not None:
        (folder / WALL_OWNER).write_text(owner + "\n", encoding="utf-8")
    return folder


def test_only_the_folders_of_hubs_that_are_gone_are_removed(tmp_path: Path) -> None:
    ours = pid_namespace()
    killed = _folder(tmp_path, 8001, f"{_dead_owner()} {ours}")
    running = _folder(tmp_path, 8002, f"{owner_tag()} {ours}")
    elsewhere = _folder(tmp_path, 8003, f"{_dead_owner()} 4026531999")  # a container's hub
    older = _folder(tmp_path, 8004, None)  # made before hubs wrote their owner
    making = tmp_path / f".{WALL_PREFIX}8005-x1y2"  # a hub's folder, not yet renamed
    making.mkdir()
    unrelated = tmp_path / f"{WALL_PREFIX}env"
    unrelated.mkdir()
    target = tmp_path / "target"
    target.mkdir()
    (tmp_path / f"{WALL_PREFIX}8006").symlink_to(target)

    assert sorted(forget_stale_wall_folders(tmp_path)) == [killed, older]
    assert not killed.exists() and not older.exists()
    for kept in (running, elsewhere, making, unrelated, target):
        assert kept.is_dir(), kept


@pytest.mark.skipif(wall_problem() is not None, reason="this host gives learners no wall")
def test_a_hub_with_the_wall_names_itself_and_clears_a_killed_hubs_folder() -> None:
    run = Path("/run") if Path("/run").is_dir() else None
    assert run is not None and os.access(run, os.W_OK)
    stale = _folder(run, free_port(), f"{_dead_owner()} {pid_namespace()}")
    port = free_port()
    try:
        on, folder = launcher._wall_sockets(port)
        assert on and folder == str(run / f"{WALL_PREFIX}{port}")
        assert not stale.exists(), "a killed hub's socket folders outlived the next hub's start"
        owner = (Path(folder) / WALL_OWNER).read_text(encoding="utf-8").split()
        assert owner == [owner_tag(), pid_namespace()]
        assert oct(Path(folder).stat().st_mode & 0o777) == "0o711"
        # its owner, this process, still runs (other tests' killed hubs' folders may go too)
        assert Path(folder) not in forget_stale_wall_folders(run) and Path(folder).is_dir()
    finally:
        shutil.rmtree(stale, ignore_errors=True)
        shutil.rmtree(run / f"{WALL_PREFIX}{port}", ignore_errors=True)
