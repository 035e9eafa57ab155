"""Issue 62, nothing lost: a file the course writes is the old one or the new one, whatever
happens (a full disk, a read-only folder, a kill at any instant), and a failure says in the
learner's words which file, why, and what to do."""

from __future__ import annotations

import errno
import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import small_disk
from small_disk import mount_namespace_prefix

from course_lib.core.errors import CourseError
from course_lib.core.files.atomic_files import (
    STALE_AFTER_S,
    TEMP_SUFFIX,
    FileSaveError,
    atomic_write,
)
from course_lib.core.paths import REPO_ROOT

SCENARIO = Path(small_disk.__file__).with_name("full_disk_writes.py")
FULL_SAID = (
    "my_files/param_vel_node.yaml was not saved: the disk is full. "
    "The file as it was before is kept.\n"
    "Try: free some space (old replays in my_files/replays/, for example), then run the cell "
    "again."
)
KILLS = 30
# Rewrites a ~2 MiB file forever with one of two texts in turn; says "written" after the first.
WRITER = """
import sys
sys.path.insert(0, sys.argv[1])
from course_lib.core.files.atomic_files import atomic_write
texts = [bytes([65 + n]) * (2 << 20) for n in range(2)]
atomic_write(sys.argv[2], texts[0].decode())
print("written", flush=True)
while True:
    for text in texts[::-1]:
        atomic_write(sys.argv[2], text.decode())
"""


def _temps(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name != "f.txt")


def test_a_full_disk_keeps_the_old_file_says_so_and_a_freed_one_saves(tmp_path: Path) -> None:
    prefix = mount_namespace_prefix()
    folder = tmp_path / "disk"
    folder.mkdir()
    command = [*prefix, sys.executable, str(SCENARIO), str(folder)]
    ran = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
    assert ran.returncode == 0, ran.stderr
    facts = json.loads(ran.stdout)

    full = facts["full"]
    assert full["type"] == "FileSaveError" and full["course_error"], full
    assert (full["errno"], full["filename"]) == (errno.ENOSPC, "my_files/param_vel_node.yaml")
    assert full["said"] == FULL_SAID
    assert facts["full_kept"] == "param_vel_node:\n  ros__parameters:\n    velocity: 0.0\n"
    assert facts["full_listing"] == ["param_vel_node.yaml"]  # no temporary file left
    assert facts["full_new_file"]["said"].startswith(
        "my_files/replays/lesson07.html was not saved: the disk is full. No file was written.\n"
    )

    assert facts["freed"] == {"type": None}  # the same write, once there is room
    assert facts["freed_text"].startswith("param_vel_node:\n  ros__parameters:\n    velocity: 0.3")
    assert facts["freed_listing"] == ["param_vel_node.yaml", "replays"]

    folder_error, file_error = facts["read_only_folder"], facts["read_only_file"]
    assert folder_error["errno"] == errno.EROFS and file_error["errno"] == errno.EROFS
    assert folder_error["said"] == (
        "my_files/new/x.yaml was not saved: that folder is read-only. No file was written.\n"
        "Try: save it under my_files/ (your own folder) instead."
    )
    assert file_error["said"].startswith("my_files/param_vel_node.yaml was not saved: that")
    assert facts["read_only_kept"] == facts["freed_text"]


def test_a_file_killed_while_rewritten_is_whole_and_leaves_one_temporary_file_at_most(
    tmp_path: Path,
) -> None:
    """Each kill lands anywhere in a write (before, during, after its rename); what a killed
    write leaves is made a minute old, so the next write removes it."""
    target = tmp_path / "f.txt"
    texts = {bytes([65 + n]) * (2 << 20) for n in range(2)}
    chance = random.Random(62)
    for kill in range(KILLS):
        command = [sys.executable, "-I", "-S", "-c", WRITER, str(REPO_ROOT), str(target)]
        writer = subprocess.Popen(command, stdout=subprocess.PIPE)
        assert writer.stdout is not None and writer.stdout.readline() == b"written\n"
        time.sleep(chance.uniform(0.0, 0.05))
        writer.send_signal(signal.SIGKILL)
        writer.wait(timeout=10)
        writer.stdout.close()
        assert target.read_bytes() in texts, f"kill {kill}: half a file"
        left = _temps(tmp_path)
        assert len(left) <= 1, f"kill {kill}: {left}"
        assert all(name.endswith(TEMP_SUFFIX) for name in left), left
        for name in left:  # as if left a minute ago: the next write removes it
            stale = time.time() - STALE_AFTER_S - 1
            os.utime(tmp_path / name, (stale, stale))
    atomic_write(target, "done\n")
    assert _temps(tmp_path) == []


def test_a_write_removes_temporary_files_left_a_minute_ago_only(tmp_path: Path) -> None:
    stale, fresh = tmp_path / f".a.yaml.x1{TEMP_SUFFIX}", tmp_path / f".b.yaml.x2{TEMP_SUFFIX}"
    someone_elses = tmp_path / ".c.yaml.x3.tmp"
    for path in (stale, fresh, someone_elses):
        path.write_text("half")
    old = time.time() - STALE_AFTER_S - 1
    for path in (stale, someone_elses):
        os.utime(path, (old, old))
    atomic_write(tmp_path / "d.yaml", "v: 1\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        [fresh.name, someone_elses.name, "d.yaml"]
    )


def test_a_folder_that_cannot_be_made_is_said_in_the_oss_words(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    Path("my_files").write_text("a file where the folder should be\n")
    with pytest.raises(FileSaveError) as raised:
        atomic_write("my_files/sub/x.yaml", "v: 1\n")
    error = raised.value
    assert isinstance(error, OSError) and isinstance(error, CourseError)
    assert error.errno in (errno.ENOTDIR, errno.EEXIST)
    assert str(error).startswith(f"my_files/sub/x.yaml was not saved: {error.strerror}.")
    assert str(error).splitlines()[0].endswith("No file was written.")


@pytest.mark.parametrize(
    ("code", "reason", "hint"),
    [
        (errno.ENOSPC, "the disk is full", "free some space (old replays in my_files/replays/"),
        (errno.EDQUOT, "your disk quota is used up", "free some space"),
        (errno.EROFS, "that folder is read-only", "save it under my_files/"),
        (errno.EACCES, "that folder cannot be written", "save it under my_files/"),
        (errno.EPERM, "that folder cannot be written", "save it under my_files/"),
        (errno.EIO, os.strerror(errno.EIO), "run the cell again"),
    ],
)
def test_each_cause_has_its_reason_and_hint(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, code: int, reason: str, hint: str
) -> None:
    monkeypatch.chdir(tmp_path)
    kept = tmp_path / "kept.yaml"
    kept.write_text("v: 0\n")
    error = FileSaveError(kept, OSError(code, os.strerror(code)))
    assert (error.reason, error.errno, error.filename) == (reason, code, str(kept))
    assert str(error) == (
        f"kept.yaml was not saved: {reason}. The file as it was before is kept.\nTry: {error.hint}"
    )
    assert error.hint.startswith(hint)
    elsewhere = FileSaveError("/nowhere/x.yaml", OSError(code, os.strerror(code)))
    assert elsewhere.shown == "/nowhere/x.yaml"  # not under the current folder: in full
