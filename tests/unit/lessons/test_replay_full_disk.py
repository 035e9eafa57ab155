"""A replay that cannot be saved (a full disk) is one line after the self-check, never a
traceback: what happened and what to do."""

from __future__ import annotations

import errno
from pathlib import Path
from types import SimpleNamespace

import pytest

from course_lib.core.files.atomic_files import FileSaveError
from course_lib.lessons.replay import show_replay


class _FullDiskRun:
    def save(self, **_options: object) -> None:
        raise FileSaveError(Path("my_files/replays/lesson07.html"), OSError(errno.ENOSPC, "full"))


def test_a_replay_on_a_full_disk_is_one_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    lesson = SimpleNamespace(replay=_FullDiskRun(), attached_world=None, state={})
    show_replay(lesson)
    said = capsys.readouterr()
    assert said.out == (
        "The replay of this run was not saved: the disk is full. Try: free some space (old "
        "replays in my_files/replays/, for example), then run the cell again.\n"
    )
    assert said.err == ""  # nothing logged with a traceback
